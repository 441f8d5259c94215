#include "vtkGLSAdaptiveBandwidth.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSRun.h"

#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"

#include "gls/AdaptiveBandwidth.h"

#include <vector>

vtkStandardNewMacro(vtkGLSAdaptiveBandwidth);

vtkGLSAdaptiveBandwidth::vtkGLSAdaptiveBandwidth()
  : ReuseInputScaleSpace(true)
  , Threshold(0.01)
  , SmoothingRadius(0.01)
{
}

vtkGLSAdaptiveBandwidth::~vtkGLSAdaptiveBandwidth() = default;

vtkGLSScaleFilterBase::SampleRequest vtkGLSAdaptiveBandwidth::GetSampleRequest(const vtkGLSRun&) const
{
  return VariationRequest(this->ReuseInputScaleSpace);
}

int vtkGLSAdaptiveBandwidth::ComputeOutputs(vtkGLSRun& run)
{
  const vtkIdType n = run.Input->GetNumberOfPoints();
  vtkNew<vtkDoubleArray> raw;
  raw->SetName(vtkGLSArrayNames::RawBandwidth);
  raw->SetNumberOfTuples(n);
  const double fitEnd = 0.9;
  const double threshold = this->Threshold;
  const std::vector<double>& t = run.Scales;
  bool aborted = !this->ReduceVariation(
    run,
    [threshold, &t](const double* nu) {
      return gls::rawBandwidth(nu, t.data(), static_cast<int>(t.size()), threshold);
    },
    raw->GetPointer(0), fitEnd);
  const vtkGLSDistributedCloud& dist = run.Distributed;
  if (dist.IsParallel())
  {
    aborted = !dist.AllTrue(!aborted); // every rank stops, or none: the ghost exchange below is collective
  }
  if (aborted)
  {
    return ABORTED; // no partial arrays
  }

  // Spatial regularization, over this piece's points and, in a distributed run, the other ranks' points within
  // the smoothing radius (ghosts, with their raw bandwidths), appended after the owned ones; coincident points count
  // once.
  const double radius = this->ToAbsoluteLength(run, this->SmoothingRadius);
  vtkGLSCloud cloud;
  cloud.Owned = static_cast<std::size_t>(n);
  cloud.Points.resize(3 * cloud.Owned);
  for (vtkIdType i = 0; i < n; ++i)
  {
    double* p = &cloud.Points[3 * static_cast<std::size_t>(i)];
    run.Input->GetPoint(i, p);
    for (int a = 0; a < 3; ++a)
    {
      p[a] -= run.Cloud.Anchor[a]; // the run's coordinates (vtkGLSCloud::Anchor)
    }
  }
  std::vector<double> rawAll(raw->GetPointer(0), raw->GetPointer(0) + n);
  std::size_t ghosts = 0;
  if (!dist.AllTrue(dist.AppendGhosts(cloud.Points, cloud.Owned, { { &rawAll, 1 } },
        radius > 0.0 ? radius : 0.0, ghosts)))
  {
    vtkErrorMacro("The exchange of ghost points between the processes failed.");
    return FAILED;
  }
  cloud.Owned += ghosts; // every point is smoothed, the ghosts' values then dropped
  if (cloud.MergeCoincident(this->NumberOfThreads) > 0)
  {
    rawAll = gls::distinctValues(cloud.Copies, rawAll.data(), 1);
  }
  std::vector<double> smoothed(rawAll.size());
  gls::ParallelOptions parallel;
  parallel.threads = this->NumberOfThreads;
  parallel.progress = [this, fitEnd](double f) { return this->ReportProgress(f, fitEnd, 1.0); };
  if (!gls::smoothBandwidth(cloud.Points.data(), rawAll.size(), rawAll.data(), radius, parallel, smoothed.data()))
  {
    return ABORTED; // (nothing collective follows): no partial arrays
  }
  std::vector<double> perPoint(cloud.InputOwned);
  cloud.ScatterToInput(smoothed.data(), 1, perPoint.data());
  vtkNew<vtkDoubleArray> bandwidth;
  bandwidth->SetName(vtkGLSArrayNames::Bandwidth);
  bandwidth->SetNumberOfTuples(n);
  std::copy(perPoint.begin(), perPoint.begin() + n, bandwidth->GetPointer(0));
  vtkPointData* pd = run.Output->GetPointData();
  pd->AddArray(raw);
  pd->AddArray(bandwidth);
  pd->SetActiveScalars(vtkGLSArrayNames::Bandwidth);
  return COMPLETED;
}

void vtkGLSAdaptiveBandwidth::DescribeSettings(std::vector<SettingRange>& settings)
{
  this->Superclass::DescribeSettings(settings);
  settings.push_back({ "Threshold", static_cast<double>(this->Threshold), static_cast<double>(0.0), static_cast<double>(VTK_DOUBLE_MAX) });
  settings.push_back({ "SmoothingRadius", static_cast<double>(this->SmoothingRadius), static_cast<double>(0.0), static_cast<double>(VTK_DOUBLE_MAX) });
}

void vtkGLSAdaptiveBandwidth::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ReuseInputScaleSpace: " << this->ReuseInputScaleSpace << "\n";
  os << indent << "Threshold: " << this->Threshold << "\n";
  os << indent << "SmoothingRadius: " << this->SmoothingRadius << "\n";
}
