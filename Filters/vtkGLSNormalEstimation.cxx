#include "vtkGLSNormalEstimation.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSScaleFilterBase.h"

#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include "gls/NormalEstimation.h"

#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkGLSNormalEstimation);

vtkGLSNormalEstimation::vtkGLSNormalEstimation()
  : NeighborhoodType(K_NEAREST)
  , NumberOfNeighbors(16)
  , Radius(0.0)
  , Orientation(MINIMUM_SPANNING_TREE)
  , OrientationPoint{ 0.0, 0.0, 0.0 }
  , GraphNeighbors(10)
  , NumberOfThreads(0)
{
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::NORMALS);
}

vtkGLSNormalEstimation::~vtkGLSNormalEstimation() = default;

int vtkGLSNormalEstimation::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkGLSNormalEstimation::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->ShallowCopy(input);

  const vtkIdType n = input->GetNumberOfPoints();
  if (n < 1)
  {
    vtkErrorMacro("The input has no points.");
    return 0;
  }
  if (this->NeighborhoodType == RADIUS && !(this->Radius > 0.0 && std::isfinite(this->Radius)))
  {
    vtkErrorMacro("Radius must be a finite positive length in RADIUS mode (got " << this->Radius << ").");
    return 0;
  }
  std::vector<double> xyz(3 * static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    input->GetPoint(i, &xyz[3 * i]);
  }

  gls::NormalEstimationSettings settings;
  settings.neighborhood = static_cast<gls::NeighborhoodType>(this->NeighborhoodType);
  settings.k = this->NumberOfNeighbors;
  settings.radius = this->Radius;
  settings.orientation = static_cast<gls::NormalOrientation>(this->Orientation);
  settings.viewpoint = { this->OrientationPoint[0], this->OrientationPoint[1], this->OrientationPoint[2] };
  settings.graphNeighbors = this->GraphNeighbors;
  settings.parallel.threads = this->NumberOfThreads;
  settings.parallel.progress = [this](double f) {
    this->UpdateProgress(0.9 * f);
    return this->GetAbortExecute() != 0;
  };

  std::vector<double> reference;
  if (this->Orientation == AGREE_WITH_EXISTING)
  {
    vtkDataArray* existing = vtkGLSScaleFilterBase::FindSelectedNormals(this, 0, input);
    if (!existing || existing->GetNumberOfComponents() != 3 || existing->GetNumberOfTuples() != n)
    {
      vtkErrorMacro("AGREE_WITH_EXISTING needs an existing 3-component point normals array with one tuple per "
                    "point (select it with SetInputArrayToProcess, or set active normals).");
      return 0;
    }
    reference.resize(3 * static_cast<std::size_t>(n));
    for (vtkIdType i = 0; i < n; ++i)
    {
      existing->GetTuple(i, &reference[3 * i]);
    }
    settings.reference = reference.data();
  }

  gls::NormalEstimationResult result;
  if (!gls::estimateNormals(xyz.data(), static_cast<std::size_t>(n), settings, result))
  {
    return 1; // aborted: the output is the input, without partial normals
  }
  vtkNew<vtkDoubleArray> normals;
  normals->SetName(vtkGLSArrayNames::Normals);
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(n);
  std::copy(result.normals.begin(), result.normals.end(), normals->GetPointer(0));
  output->GetPointData()->SetNormals(normals);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkGLSNormalEstimation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NeighborhoodType: " << (this->NeighborhoodType == K_NEAREST ? "KNearest" : "Radius") << "\n";
  os << indent << "NumberOfNeighbors: " << this->NumberOfNeighbors << "\n";
  os << indent << "Radius: " << this->Radius << "\n";
  os << indent << "Orientation: " << this->Orientation << "\n";
  os << indent << "OrientationPoint: " << this->OrientationPoint[0] << ", " << this->OrientationPoint[1] << ", "
     << this->OrientationPoint[2] << "\n";
  os << indent << "GraphNeighbors: " << this->GraphNeighbors << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
}
