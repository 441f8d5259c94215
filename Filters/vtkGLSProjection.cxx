#include "vtkGLSProjection.h"

#include "vtkGLSArrayNames.h"

#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include "gls/MlsProjection.h"

#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkGLSProjection);

vtkGLSProjection::vtkGLSProjection()
  : ScaleMode(AUTOMATIC)
  , Scale(0.01)
  , MaxIterations(50)
  , Tolerance(1e-6)
{
  this->SetInputArrayToProcess(
    1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkGLSArrayNames::Bandwidth);
}

vtkGLSProjection::~vtkGLSProjection() = default;

int vtkGLSProjection::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->LastScaleMode = AUTOMATIC;
  if (!this->PrepareOutput(input, output))
  {
    return 0;
  }
  std::vector<double> points, normals;
  if (!this->GatherPointsAndNormals(input, points, normals))
  {
    return 0;
  }
  const vtkIdType n = input->GetNumberOfPoints();
  const std::size_t count = static_cast<std::size_t>(n);

  const char* selected = SelectedArrayName(this, 1);
  vtkDataArray* bandwidth = input->GetPointData()->GetArray(selected ? selected : vtkGLSArrayNames::Bandwidth);
  int mode = this->ScaleMode;
  if (mode == AUTOMATIC)
  {
    if (!bandwidth)
    {
      // A selection made before the input's arrays were known (a script that did not update the input first).
      bandwidth = input->GetPointData()->GetArray(vtkGLSArrayNames::Bandwidth);
    }
    mode = bandwidth ? BANDWIDTH_ARRAY : FIXED_SCALE;
  }
  std::vector<double> scales(count);
  if (mode == BANDWIDTH_ARRAY)
  {
    if (!bandwidth)
    {
      vtkErrorMacro("No bandwidth array: run GLS Adaptive Bandwidth first (it writes GLSBandwidth), select the "
                    "array with SetInputArrayToProcess(1, ...), or use ScaleMode FIXED_SCALE.");
      return 0;
    }
    if (bandwidth->GetNumberOfComponents() != 1 || bandwidth->GetNumberOfTuples() != n)
    {
      vtkErrorMacro("The bandwidth array " << (bandwidth->GetName() ? bandwidth->GetName() : "(unnamed)")
                                           << " must have 1 component and " << n << " tuples; it has "
                                           << bandwidth->GetNumberOfComponents() << " and "
                                           << bandwidth->GetNumberOfTuples() << ".");
      return 0;
    }
    for (vtkIdType i = 0; i < n; ++i)
    {
      scales[static_cast<std::size_t>(i)] = bandwidth->GetComponent(i, 0);
    }
  }
  else
  {
    const double t = this->ToAbsoluteLength(input, this->Scale);
    if (!(t > 0.0) || !std::isfinite(t))
    {
      vtkErrorMacro("Scale must be positive (it is " << this->Scale
                                                     << (this->ScaleUnits == RELATIVE_TO_DIAGONAL
                                                            ? " of the bounding-box diagonal)."
                                                            : ")."));
      return 0;
    }
    std::fill(scales.begin(), scales.end(), t);
  }
  // Outputs plus the core's copies of points and normals and its grid.
  if (!this->CheckMemoryBudget(static_cast<double>(count) * (3 * 8 + 3 * 8 + 8 + 4 + 1 + 7 * 8),
        "the projection", "Use fewer points."))
  {
    return 0;
  }

  vtkNew<vtkPoints> moved;
  moved->SetDataTypeToDouble();
  moved->SetNumberOfPoints(n);
  vtkNew<vtkDoubleArray> eta;
  eta->SetName(vtkGLSArrayNames::Normals);
  eta->SetNumberOfComponents(3);
  eta->SetNumberOfTuples(n);
  vtkNew<vtkDoubleArray> displacement;
  displacement->SetName(vtkGLSArrayNames::Displacement);
  displacement->SetNumberOfTuples(n);
  vtkNew<vtkIntArray> iterations;
  iterations->SetName(vtkGLSArrayNames::ProjectionIterations);
  iterations->SetNumberOfTuples(n);
  std::vector<unsigned char> converged(count);

  gls::ProjectionSettings settings;
  settings.minNeighbors = this->ResolveMinimumNeighbors(points, normals);
  settings.maxIterations = this->MaxIterations;
  settings.tolerance = this->Tolerance;
  settings.parallel.threads = this->NumberOfThreads;
  settings.parallel.chunk = 64;
  settings.parallel.progress = [this](double f) { return this->ReportProgress(f, 0.0, 1.0); };
  const gls::ProjectionOutputs out{ static_cast<double*>(moved->GetData()->GetVoidPointer(0)), eta->GetPointer(0),
    displacement->GetPointer(0), iterations->GetPointer(0), converged.data() };
  if (!gls::projectPointCloud(points.data(), normals.data(), count, scales.data(), settings, out))
  {
    return 1; // aborted: the input passes through, no partial arrays
  }
  this->LastScaleMode = mode;
  output->SetPoints(moved);
  vtkPointData* pd = output->GetPointData();
  pd->RemoveArray(vtkGLSArrayNames::Normals);
  pd->AddArray(eta);
  pd->SetNormals(eta);
  pd->AddArray(displacement);
  pd->AddArray(iterations);
  pd->SetActiveScalars(vtkGLSArrayNames::Displacement);
  this->LastBackendUsed = "CPU";
  this->StoreBackend(output->GetFieldData());
  return 1;
}

void vtkGLSProjection::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ScaleMode: " << this->ScaleMode << "\n";
  os << indent << "Scale: " << this->Scale << "\n";
  os << indent << "MaxIterations: " << this->MaxIterations << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
}
