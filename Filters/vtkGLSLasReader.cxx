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

vtkIdType vtkGLSLasReader::ReadAnnouncedPointCount()
{
  std::ifstream in(this->FileName, std::ios::binary);
  if (this->FileName.empty() || !in)
  {
    return -1;
  }
  in.seekg(0, std::ios::end);
  gls::LasHeader h;
  std::string error;
  return gls::readLasHeader(in, static_cast<std::uint64_t>(in.tellg()), h, error)
    ? static_cast<vtkIdType>(h.pointCount)
    : -1;
}

namespace
{

/// The point arrays of a LAS file's points: those of every format, and GpsTime, RGB, NIR and the extra bytes where
/// the file has them.
struct LasArrays
{
  vtkSmartPointer<vtkDoubleArray> xyz;
  std::vector<vtkSmartPointer<vtkDataArray>> attributes; ///< the point arrays, in output order
  gls::LasColumns columns;                               ///< where readLasPoints writes each

  LasArrays(const gls::LasHeader& h, vtkIdType n)
  {
    xyz = newArray<vtkDoubleArray>("Points", 3, n);
    auto intensity = newArray<vtkUnsignedShortArray>("Intensity", 1, n);
    auto returnNumber = newArray<vtkUnsignedCharArray>("ReturnNumber", 1, n);
    auto returns = newArray<vtkUnsignedCharArray>("NumberOfReturns", 1, n);
    auto classification = newArray<vtkUnsignedCharArray>("Classification", 1, n);
    auto angle = newArray<vtkFloatArray>("ScanAngle", 1, n);
    auto user = newArray<vtkUnsignedCharArray>("UserData", 1, n);
    auto source = newArray<vtkUnsignedShortArray>("PointSourceId", 1, n);
    attributes = { intensity, returnNumber, returns, classification, angle, user, source };
    columns.xyz = xyz->GetPointer(0);
    columns.intensity = intensity->GetPointer(0);
    columns.returnNumber = returnNumber->GetPointer(0);
    columns.numberOfReturns = returns->GetPointer(0);
    columns.classification = classification->GetPointer(0);
    columns.scanAngle = angle->GetPointer(0);
    columns.userData = user->GetPointer(0);
    columns.pointSourceId = source->GetPointer(0);
    if (h.hasGpsTime())
    {
      auto gps = newArray<vtkDoubleArray>("GpsTime", 1, n);
      columns.gpsTime = gps->GetPointer(0);
      attributes.push_back(gps);
    }
    if (h.hasRgb())
    {
      auto rgb = newArray<vtkUnsignedShortArray>("RGB", 3, n);
      columns.rgb = rgb->GetPointer(0);
      attributes.push_back(rgb);
    }
    if (h.hasNir())
    {
      auto nir = newArray<vtkUnsignedShortArray>("NIR", 1, n);
      columns.nir = nir->GetPointer(0);
      attributes.push_back(nir);
    }
    for (const gls::LasExtraBytes& x : h.extra)
    {
      auto extra = newArray<vtkDoubleArray>(x.name.c_str(), 1, n);
      columns.extra.push_back(extra->GetPointer(0));
      attributes.push_back(extra);
    }
  }

  /// The points, one vertex cell each, and the point arrays into `output`.
  void moveInto(vtkPolyData* output, vtkIdType n) const
  {
    vtkNew<vtkPoints> points;
    points->SetData(xyz);
    output->SetPoints(points);
    output->SetVerts(vtkGLSVertexCells(n));
    for (const auto& a : attributes)
    {
      output->GetPointData()->AddArray(a);
    }
  }
};

} // namespace

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
  LasArrays arrays(h, n);
  if (!gls::readLasPoints(in, h, arrays.columns, error))
  {
    vtkErrorMacro("Cannot read the LAS file '" << this->FileName << "': " << error << ".");
    return 0;
  }
  arrays.moveInto(output, n);
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
