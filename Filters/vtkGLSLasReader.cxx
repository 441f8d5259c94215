#include "vtkGLSLasReader.h"

#include "vtkGLSReaderParts.h"

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include "gls/LasFile.h"

#include <algorithm>
#include <fstream>
#include <sstream>

vtkStandardNewMacro(vtkGLSLasReader);

namespace
{

template <class Array>
vtkSmartPointer<Array> newArray(const char* name, int components, vtkIdType n)
{
  auto array = vtkSmartPointer<Array>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(n);
  return array;
}

} // namespace

vtkGLSLasReader::vtkGLSLasReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkGLSLasReader::~vtkGLSLasReader() = default;

int vtkGLSLasReader::CanReadFile(const char* name)
{
  const std::string ext = vtkGLSFileExtension(name);
  return ext == "las" || ext == "laz";
}

int vtkGLSLasReader::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->Description.clear();
  std::ifstream in(this->FileName, std::ios::binary);
  if (this->FileName.empty() || !in)
  {
    vtkErrorMacro("Cannot open the LAS file '" << this->FileName << "'.");
    return 0;
  }
  in.seekg(0, std::ios::end);
  const std::uint64_t size = static_cast<std::uint64_t>(in.tellg());
  gls::LasHeader h;
  std::string error;
  if (!gls::readLasHeader(in, size, h, error))
  {
    vtkErrorMacro("Cannot read the LAS file '" << this->FileName << "': " << error << ".");
    return 0;
  }
  const vtkIdType n = static_cast<vtkIdType>(h.pointCount);
  auto xyz = newArray<vtkDoubleArray>("Points", 3, n);
  auto intensity = newArray<vtkUnsignedShortArray>("Intensity", 1, n);
  auto returnNumber = newArray<vtkUnsignedCharArray>("ReturnNumber", 1, n);
  auto returns = newArray<vtkUnsignedCharArray>("NumberOfReturns", 1, n);
  auto classification = newArray<vtkUnsignedCharArray>("Classification", 1, n);
  auto angle = newArray<vtkFloatArray>("ScanAngle", 1, n);
  auto user = newArray<vtkUnsignedCharArray>("UserData", 1, n);
  auto source = newArray<vtkUnsignedShortArray>("PointSourceId", 1, n);
  auto gps = newArray<vtkDoubleArray>("GpsTime", 1, h.hasGpsTime() ? n : 0);
  auto rgb = newArray<vtkUnsignedShortArray>("RGB", 3, h.hasRgb() ? n : 0);
  auto nir = newArray<vtkUnsignedShortArray>("NIR", 1, h.hasNir() ? n : 0);
  gls::LasColumns columns;
  columns.xyz = xyz->GetPointer(0);
  columns.intensity = intensity->GetPointer(0);
  columns.returnNumber = returnNumber->GetPointer(0);
  columns.numberOfReturns = returns->GetPointer(0);
  columns.classification = classification->GetPointer(0);
  columns.scanAngle = angle->GetPointer(0);
  columns.userData = user->GetPointer(0);
  columns.pointSourceId = source->GetPointer(0);
  columns.gpsTime = h.hasGpsTime() ? gps->GetPointer(0) : nullptr;
  columns.rgb = h.hasRgb() ? rgb->GetPointer(0) : nullptr;
  columns.nir = h.hasNir() ? nir->GetPointer(0) : nullptr;
  std::vector<vtkSmartPointer<vtkDoubleArray>> extra;
  for (const gls::LasExtraBytes& x : h.extra)
  {
    extra.push_back(newArray<vtkDoubleArray>(x.name.c_str(), 1, n));
    columns.extra.push_back(extra.back()->GetPointer(0));
  }
  if (!gls::readLasPoints(in, h, columns, error))
  {
    vtkErrorMacro("Cannot read the LAS file '" << this->FileName << "': " << error << ".");
    return 0;
  }
  vtkNew<vtkPoints> points;
  points->SetData(xyz);
  output->SetPoints(points);
  output->SetVerts(vtkGLSVertexCells(n));
  vtkPointData* pd = output->GetPointData();
  for (vtkDataArray* a : { static_cast<vtkDataArray*>(intensity), static_cast<vtkDataArray*>(returnNumber),
         static_cast<vtkDataArray*>(returns), static_cast<vtkDataArray*>(classification),
         static_cast<vtkDataArray*>(angle), static_cast<vtkDataArray*>(user), static_cast<vtkDataArray*>(source) })
  {
    pd->AddArray(a);
  }
  if (h.hasGpsTime())
  {
    pd->AddArray(gps);
  }
  if (h.hasRgb())
  {
    pd->AddArray(rgb);
  }
  if (h.hasNir())
  {
    pd->AddArray(nir);
  }
  for (const auto& a : extra)
  {
    pd->AddArray(a);
  }
  std::ostringstream d;
  d << "LAS " << h.versionMajor << "." << h.versionMinor << ", point format " << h.format << ", " << h.pointCount
    << " points";
  this->Description = d.str();
  return 1;
}

void vtkGLSLasReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Description: " << this->Description << "\n";
}
