#include "vtkGLSAdaptiveBandwidth.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSDistributedCloud.h"

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
  const vtkGLSDistributedCloud& dist = this->Distributed();
  if (dist.IsParallel())
  {
    aborted = !dist.AllTrue(!aborted); // every rank stops, or none: the ghost exchange below is collective
  }
  if (aborted)
  {
    return 1; // no partial arrays
  }

  // Spatial regularization, over this piece's points and, in a distributed run, the other ranks' points within
  // the smoothing radius (ghosts, with their raw bandwidths), appended after the owned ones.
  const double radius = this->ToAbsoluteLength(input, this->SmoothingRadius);
  std::vector<double> xyz(3 * static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    input->GetPoint(i, &xyz[3 * static_cast<std::size_t>(i)]);
  }
  std::vector<double> rawAll(raw->GetPointer(0), raw->GetPointer(0) + n);
  if (dist.IsParallel())
  {
    std::vector<double> rows(4 * static_cast<std::size_t>(n)), ghosts;
    for (vtkIdType i = 0; i < n; ++i)
    {
      std::copy(&xyz[3 * i], &xyz[3 * i] + 3, &rows[4 * i]);
      rows[4 * i + 3] = rawAll[i];
    }
    std::size_t ghostCount = 0;
    if (!dist.AllTrue(dist.ExchangeGhosts(rows.data(), static_cast<std::size_t>(n), 4,
          radius > 0.0 ? radius : 0.0, ghosts, ghostCount)))
    {
      vtkErrorMacro("The exchange of ghost points between the processes failed.");
      return 0;
    }
    for (std::size_t g = 0; g < ghostCount; ++g)
    {
      xyz.insert(xyz.end(), &ghosts[4 * g], &ghosts[4 * g] + 3);
      rawAll.push_back(ghosts[4 * g + 3]);
    }
  }
  std::vector<double> smoothed(rawAll.size());
  gls::ParallelOptions parallel;
  parallel.threads = this->NumberOfThreads;
  parallel.progress = [this, fitEnd](double f) { return this->ReportProgress(f, fitEnd, 1.0); };
  if (!gls::smoothBandwidth(xyz.data(), rawAll.size(), rawAll.data(), radius, parallel, smoothed.data()))
  {
    return 1; // aborted (nothing collective follows): no partial arrays
  }
  vtkNew<vtkDoubleArray> bandwidth;
  bandwidth->SetName(vtkGLSArrayNames::Bandwidth);
  bandwidth->SetNumberOfTuples(n);
  std::copy(smoothed.begin(), smoothed.begin() + n, bandwidth->GetPointer(0));
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
