#include "vtkGLSAdaptiveBandwidth.h"

#include "vtkGLSArrayNames.h"

#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include "gls/AdaptiveBandwidth.h"

#include <vector>

vtkStandardNewMacro(vtkGLSAdaptiveBandwidth);

vtkGLSAdaptiveBandwidth::vtkGLSAdaptiveBandwidth()
  : Threshold(0.01)
  , SmoothingRadius(0.01)
{
}

vtkGLSAdaptiveBandwidth::~vtkGLSAdaptiveBandwidth() = default;

int vtkGLSAdaptiveBandwidth::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!this->PrepareOutput(input, output))
  {
    return 0;
  }
  const vtkIdType n = input->GetNumberOfPoints();
  vtkNew<vtkDoubleArray> raw;
  raw->SetName(vtkGLSArrayNames::RawBandwidth);
  raw->SetNumberOfTuples(n);
  const double fitEnd = 0.9;
  const double threshold = this->Threshold;
  std::vector<double> scales;
  bool aborted = false;
  if (!this->ReduceVariationPerPoint(
        input,
        [threshold](const double* nu, const std::vector<double>& t) {
          return gls::rawBandwidth(nu, t.data(), static_cast<int>(t.size()), threshold);
        },
        scales, raw->GetPointer(0), fitEnd, aborted))
  {
    return 0;
  }
  if (aborted)
  {
    return 1; // no partial arrays
  }

  // Spatial regularization.
  std::vector<double> xyz(3 * static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    input->GetPoint(i, &xyz[3 * static_cast<std::size_t>(i)]);
  }
  vtkNew<vtkDoubleArray> bandwidth;
  bandwidth->SetName(vtkGLSArrayNames::Bandwidth);
  bandwidth->SetNumberOfTuples(n);
  gls::ParallelOptions parallel;
  parallel.threads = this->NumberOfThreads;
  parallel.progress = [this, fitEnd](double f) { return this->ReportProgress(f, fitEnd, 1.0); };
  const double radius = this->ToAbsoluteLength(input, this->SmoothingRadius);
  if (!gls::smoothBandwidth(
        xyz.data(), static_cast<std::size_t>(n), raw->GetPointer(0), radius, parallel, bandwidth->GetPointer(0)))
  {
    return 1; // aborted: no partial arrays
  }
  output->GetPointData()->AddArray(raw);
  output->GetPointData()->AddArray(bandwidth);
  output->GetPointData()->SetActiveScalars(vtkGLSArrayNames::Bandwidth);
  StoreScales(output->GetFieldData(), scales);
  this->StoreBackend(output->GetFieldData());
  return 1;
}

void vtkGLSAdaptiveBandwidth::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Threshold: " << this->Threshold << "\n";
  os << indent << "SmoothingRadius: " << this->SmoothingRadius << "\n";
}
