#include "vtkGLSPointCloudReader.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSReaderParts.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include "gls/PointTextParser.h"

#include <algorithm>
#include <fstream>
#include <numeric>
#include <set>

vtkStandardNewMacro(vtkGLSPointCloudReader);

namespace
{

/// A point array named `name` holding `values` (components per tuple), copied.
template <class Array, class T>
vtkSmartPointer<Array> pointArray(const char* name, int components, const std::vector<T>& values)
{
  auto array = vtkSmartPointer<Array>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / components));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  return array;
}

} // namespace

vtkGLSPointCloudReader::vtkGLSPointCloudReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkGLSPointCloudReader::~vtkGLSPointCloudReader() = default;

int vtkGLSPointCloudReader::CanReadFile(const char* name)
{
  const std::string ext = vtkGLSFileExtension(name);
  if (ext == "csv" || ext == "txt")
  {
    return gls::pointCloudFileHeadError(name).empty();
  }
  return ext == "xyz" || ext == "pts" || ext == "ptx" || ext == "pcd";
}

vtkIdType vtkGLSPointCloudReader::ReadAnnouncedPointCount()
{
  std::ifstream in(this->FileName, std::ios::binary);
  if (vtkGLSFileExtension(this->FileName.c_str()) != "pcd" || !in)
  {
    return -1;
  }
  std::string head(gls::pointCloudHeadBytes, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  return static_cast<vtkIdType>(gls::pcdAnnouncedPoints(head.data(), static_cast<std::size_t>(in.gcount())));
}

int vtkGLSPointCloudReader::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->ColumnLayout.clear();
  if (this->FileName.empty())
  {
    vtkErrorMacro("No FileName set.");
    return 0;
  }
  const std::string ext = vtkGLSFileExtension(this->FileName.c_str());
  const gls::PointText text = ext == "ptx" ? gls::readPtxFile(this->FileName)
    : ext == "pcd"                         ? gls::readPcdFile(this->FileName)
                                           : gls::readPointTextFile(this->FileName);
  if (!text.error.empty())
  {
    vtkErrorMacro("Cannot read the point cloud: " << text.error);
    return 0;
  }
  if (!text.warning.empty())
  {
    vtkWarningMacro("" << text.warning);
  }
  this->ColumnLayout = text.layout;
  const vtkIdType n = static_cast<vtkIdType>(text.points.size() / 3);
  vtkNew<vtkPoints> points;
  points->SetData(pointArray<vtkDoubleArray>("Points", 3, text.points));
  output->SetPoints(points);
  output->SetVerts(vtkGLSVertexCells(n));

  vtkPointData* pd = output->GetPointData();
  std::set<std::string> names;
  if (!text.normals.empty())
  {
    pd->SetNormals(pointArray<vtkDoubleArray>(vtkGLSArrayNames::Normals, 3, text.normals));
    names.insert(vtkGLSArrayNames::Normals);
  }
  if (!text.colors.empty())
  {
    pd->SetScalars(pointArray<vtkUnsignedCharArray>(vtkGLSArrayNames::Colors, 3, text.colors));
    names.insert(vtkGLSArrayNames::Colors);
  }
  if (!text.intensity.empty())
  {
    pd->AddArray(pointArray<vtkFloatArray>(vtkGLSArrayNames::Intensity, 1, text.intensity));
    names.insert(vtkGLSArrayNames::Intensity);
  }
  if (!text.viewpoints.empty())
  {
    pd->AddArray(pointArray<vtkDoubleArray>(vtkGLSArrayNames::ScannerPosition, 3, text.viewpoints));
    names.insert(vtkGLSArrayNames::ScannerPosition);
  }
  if (text.hasSensor)
  {
    vtkNew<vtkDoubleArray> sensor; // one tuple: the sensor of every point (a PCD's VIEWPOINT)
    sensor->SetName(vtkGLSArrayNames::ScannerPosition);
    sensor->SetNumberOfComponents(3);
    sensor->InsertNextTuple(text.sensor);
    output->GetFieldData()->AddArray(sensor);
  }
  for (const gls::PointTextColumn& column : text.otherColumns)
  {
    // A name already taken (twice in the header, or one of the arrays above) gets a suffix, so no data is lost.
    std::string name = column.name;
    for (int k = 2; names.count(name); ++k)
    {
      name = column.name + " (" + std::to_string(k) + ")";
    }
    names.insert(name);
    pd->AddArray(pointArray<vtkDoubleArray>(name.c_str(), 1, column.values));
  }
  return 1;
}

void vtkGLSPointCloudReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "ColumnLayout: " << this->ColumnLayout << "\n";
}
