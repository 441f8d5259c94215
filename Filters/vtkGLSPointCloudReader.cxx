#include "vtkGLSPointCloudReader.h"

#include "vtkGLSArrayNames.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include "gls/PointTextParser.h"

#include <algorithm>
#include <cctype>
#include <numeric>

vtkStandardNewMacro(vtkGLSPointCloudReader);

vtkGLSPointCloudReader::vtkGLSPointCloudReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkGLSPointCloudReader::~vtkGLSPointCloudReader() = default;

int vtkGLSPointCloudReader::CanReadFile(const char* name)
{
  std::string path = name ? name : "";
  const auto dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == "xyz" || ext == "pts" || ext == "csv" || ext == "txt";
}

int vtkGLSPointCloudReader::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (this->FileName.empty())
  {
    vtkErrorMacro("No FileName set.");
    return 0;
  }
  const gls::PointText text = gls::readPointTextFile(this->FileName);
  if (!text.error.empty())
  {
    vtkErrorMacro("Cannot read the point cloud: " << text.error);
    return 0;
  }
  const vtkIdType n = static_cast<vtkIdType>(text.points.size() / 3);
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(n);
  std::copy(text.points.begin(), text.points.end(), coordinates->GetPointer(0));
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  output->SetPoints(points);

  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfTuples(n + 1);
  connectivity->SetNumberOfTuples(n);
  std::iota(offsets->GetPointer(0), offsets->GetPointer(0) + n + 1, vtkIdType(0));
  std::iota(connectivity->GetPointer(0), connectivity->GetPointer(0) + n, vtkIdType(0));
  vtkNew<vtkCellArray> verts;
  verts->SetData(offsets, connectivity);
  output->SetVerts(verts);

  if (!text.normals.empty())
  {
    vtkNew<vtkDoubleArray> normals;
    normals->SetName(vtkGLSArrayNames::Normals);
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(n);
    std::copy(text.normals.begin(), text.normals.end(), normals->GetPointer(0));
    output->GetPointData()->SetNormals(normals);
  }
  return 1;
}

void vtkGLSPointCloudReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
}
