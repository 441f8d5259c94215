#include "vtkGLSContinuousFeatures.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSRun.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"

#include "gls/Descriptors.h"
#include "gls/ScaleAnalysis.h"
#include "gls/ScaleSpaceEngine.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

vtkStandardNewMacro(vtkGLSContinuousFeatures);

namespace
{

/// Keeps nu of a sample of points (the ids given, in increasing order), one row of S values each.
class SampleVariationSink : public gls::ScaleSampleSink
{
public:
  SampleVariationSink(const std::vector<std::uint64_t>& ids, const std::vector<double>& scales,
    const gls::VariationWeights& weights)
    : Ids(ids)
    , Scales(scales)
    , Weights(weights)
    , Nu(ids.size() * scales.size())
  {
  }
  void consume(std::uint64_t id, const gls::ScaleSample* s, int) override
  {
    const std::size_t row = static_cast<std::size_t>(
      std::lower_bound(this->Ids.begin(), this->Ids.end(), id) - this->Ids.begin());
    for (std::size_t k = 0; k < this->Scales.size(); ++k)
    {
      this->Nu[row * this->Scales.size() + k] = gls::geometricVariation(s[k], this->Scales[k], this->Weights);
    }
  }
  const std::vector<std::uint64_t>& Ids;
  const std::vector<double>& Scales;
  gls::VariationWeights Weights;
  std::vector<double> Nu;
};

constexpr double kSigmaSampleSize = 20000;

}

vtkGLSContinuousFeatures::vtkGLSContinuousFeatures()
  : ReuseInputScaleSpace(true)
  , SigmaMode(SIGMA_RELATIVE)
  , Sigma(0.1)
  , TargetMedianFeature(0.28)
  , LastSigma(std::numeric_limits<double>::quiet_NaN())
  , FeatureMeasure(SCALE)
{
}

vtkGLSContinuousFeatures::~vtkGLSContinuousFeatures() = default;

bool vtkGLSContinuousFeatures::CheckParameters(vtkGLSRun& run)
{
  if (!this->Superclass::CheckParameters(run))
  {
    return false;
  }
  if (this->SigmaMode == SIGMA_ABSOLUTE && (!(this->Sigma > 0.0) || !std::isfinite(this->Sigma)))
  {
    vtkErrorMacro("Sigma must be a positive finite number (it is " << this->Sigma
                                                                  << "): it is the scale of tanh(nu / Sigma).");
    return false;
  }
  if (this->SigmaMode == SIGMA_RELATIVE && !(this->TargetMedianFeature > 0.0 && this->TargetMedianFeature < 1.0))
  {
    vtkErrorMacro("TargetMedianFeature must be strictly between 0 and 1 (it is " << this->TargetMedianFeature
                                                                                << ").");
    return false;
  }
  return true;
}

vtkGLSScaleFilterBase::SampleRequest vtkGLSContinuousFeatures::GetSampleRequest(const vtkGLSRun&) const
{
  return VariationRequest(this->ReuseInputScaleSpace);
}

int vtkGLSContinuousFeatures::ComputeOutputs(vtkGLSRun& run)
{
  this->LastSigma = std::numeric_limits<double>::quiet_NaN();
  double sigma = this->Sigma;
  if (this->SigmaMode == SIGMA_RELATIVE && !this->RelativeSigma(run, sigma))
  {
    return ABORTED;
  }
  vtkNew<vtkDoubleArray> feature;
  feature->SetName(vtkGLSArrayNames::Feature);
  feature->SetNumberOfTuples(run.Input->GetNumberOfPoints());
  const gls::FeatureMeasure measure = static_cast<gls::FeatureMeasure>(this->FeatureMeasure);
  const std::vector<double>& t = run.Scales;
  if (!this->ReduceVariation(
        run,
        [sigma, measure, &t](const double* nu) {
          return gls::continuousFeature(nu, t.data(), static_cast<int>(t.size()), sigma, measure);
        },
        feature->GetPointer(0), 1.0))
  {
    return ABORTED; // no partial arrays
  }
  this->LastSigma = sigma;
  run.Output->GetPointData()->AddArray(feature);
  run.Output->GetPointData()->SetActiveScalars(vtkGLSArrayNames::Feature);
  vtkNew<vtkDoubleArray> used;
  used->SetName(vtkGLSArrayNames::Sigma);
  used->InsertNextValue(sigma);
  run.Output->GetFieldData()->AddArray(used);
  return COMPLETED;
}

bool vtkGLSContinuousFeatures::RelativeSigma(vtkGLSRun& run, double& sigma)
{
  // The sample: every k-th point by global id (the serial index in a serial run), at most 20,000 points.
  const vtkGLSDistributedCloud& dist = run.Distributed;
  const long long n = run.Input->GetNumberOfPoints();
  const double total = dist.Sum(static_cast<double>(n));
  const long long stride = std::max(1LL, static_cast<long long>(std::ceil(total / kSigmaSampleSize)));
  std::vector<std::uint64_t> ids;
  long long offset = 0;
  if (dist.RankOrderIds(run.Input, offset))
  {
    // Ids offset + i: the multiples of the stride, without listing every id (a 10M-point cloud: 0.16 s).
    for (long long i = (stride - offset % stride) % stride; i < n; i += stride)
    {
      ids.push_back(static_cast<std::uint64_t>(i));
    }
  }
  else
  {
    const std::vector<long long> global = dist.GlobalIds(run.Input);
    for (std::size_t i = 0; i < global.size(); ++i)
    {
      if (global[i] % stride == 0)
      {
        ids.push_back(static_cast<std::uint64_t>(i));
      }
    }
  }
  const std::size_t S = run.Scales.size();
  std::vector<double> nu(ids.size() * S);
  if (run.StoredVariation)
  {
    for (std::size_t r = 0; r < ids.size(); ++r)
    {
      run.StoredVariation->GetTuple(static_cast<vtkIdType>(ids[r]), &nu[r * S]);
    }
  }
  else
  {
    SampleVariationSink sink(ids, run.Scales, this->Weights());
    const bool completed = this->FeedSamples(run, sink, &ids, 0.0, 0.05);
    if (!dist.AllTrue(completed))
    {
      return false;
    }
    nu = std::move(sink.Nu);
  }
  // Every rank's rows on rank 0, which finds sigma and shares it.
  std::vector<double> all;
  std::vector<long long> counts;
  if (!dist.GatherRows(nu, static_cast<int>(S), 0, all, counts))
  {
    all.clear();
  }
  double mine = -std::numeric_limits<double>::infinity();
  if (dist.GetRank() == 0)
  {
    mine = gls::sigmaForMedianFeature(all, all.size() / std::max<std::size_t>(S, 1), run.Scales.data(),
      static_cast<int>(S), static_cast<gls::FeatureMeasure>(this->FeatureMeasure), this->TargetMedianFeature);
    if (std::isnan(mine))
    {
      mine = gls::kMinimumRelativeSigma; // no defined feature anywhere: f is NaN whatever sigma
    }
  }
  sigma = dist.Max(mine);
  return true;
}

void vtkGLSContinuousFeatures::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ReuseInputScaleSpace: " << this->ReuseInputScaleSpace << "\n";
  os << indent << "SigmaMode: " << (this->SigmaMode == SIGMA_RELATIVE ? "Relative" : "Absolute") << "\n";
  os << indent << "Sigma: " << this->Sigma << "\n";
  os << indent << "TargetMedianFeature: " << this->TargetMedianFeature << "\n";
  os << indent << "FeatureMeasure: " << (this->FeatureMeasure == SCALE ? "Scale" : "LogScale") << "\n";
}
