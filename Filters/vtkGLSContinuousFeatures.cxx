#include "vtkGLSContinuousFeatures.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSOutputPrecision.h"
#include "vtkGLSRun.h"
#include "vtkGLSSteadiestDirections.h"

#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkSmartPointer.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"

#include "gls/Descriptors.h"
#include "gls/ScaleAnalysis.h"
#include "gls/ScaleSpaceEngine.h"
#include "gls/SinkPair.h"
#include "gls/VariationSink.h"

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

/// The summary's arrays of values (GLSStableScale, tau, kappa, phi, GLSMaxVariation and its scale), besides its int
/// count.
constexpr double kSummaryValueArrays = 6.0;

}

vtkGLSContinuousFeatures::vtkGLSContinuousFeatures()
  : ReuseInputScaleSpace(true)
  , ScaleSummary(false)
  , DirectionSummary(false)
  , AnisotropyThreshold(gls::kSignificantAnisotropy)
  , SigmaMode(SIGMA_RELATIVE)
  , Sigma(0.1)
  , TargetMedianFeature(0.28)
  , LastSigma(std::numeric_limits<double>::quiet_NaN())
  , FeatureMeasure(SCALE)
  , OutputPrecision(vtkAlgorithm::DOUBLE_PRECISION)
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
  if (this->DirectionSummary && !this->ScaleSummary)
  {
    vtkErrorMacro("DirectionSummary writes the steadiest principal directions beside the scale summary: turn "
                  "ScaleSummary on too, or use GLS Principal Directions (vtkGLSPrincipalDirections) alone.");
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

vtkGLSScaleFilterBase::SampleRequest vtkGLSContinuousFeatures::GetSampleRequest(const vtkGLSRun& run) const
{
  SampleRequest request = VariationRequest(this->ReuseInputScaleSpace);
  const double value = vtkGLSOutputPrecision::ValueBytes(this->OutputPrecision);
  if (this->ScaleSummary)
  {
    request.Descriptors = true; // tau, kappa and phi at the stable scale
    request.VariationWillDo = false;
    request.BytesPerPoint = kSummaryValueArrays * value + sizeof(int);
  }
  // GLSFeature (as doubles until it is narrowed, without the summary)
  request.BytesPerPoint += this->ScaleSummary ? value : sizeof(double) + value;
  if (this->SigmaMode == SIGMA_RELATIVE)
  {
    // nu of the sigma's sample, in the sink and gathered for the median.
    const double rows = std::min(kSigmaSampleSize, static_cast<double>(run.Input->GetNumberOfPoints()));
    request.BytesPerScale = 2.0 * rows * sizeof(double);
  }
  if (this->DirectionSummary)
  {
    request.PrincipalCurvatures = true;
    request.BytesPerPoint += vtkGLSSteadiestDirections::kSteadiestValues * value;
  }
  request.What = this->DirectionSummary
    ? "the continuous features, their scale summary and the steadiest principal directions"
    : (this->ScaleSummary ? "the continuous features and their scale summary" : "the continuous features");
  request.Advice = "Use fewer scales (NumberOfScales), or an absolute sigma (SigmaMode Absolute), whose sample "
                   "of nu is not needed.";
  return request;
}

int vtkGLSContinuousFeatures::ComputeOutputs(vtkGLSRun& run)
{
  if (run.Scales.size() < 2)
  {
    // f integrates nu over the scales (log t): one scale gives no interval, and NaN everywhere.
    vtkErrorMacro("The continuous features need at least 2 scales (there is " << run.Scales.size()
                                                                               << "): raise NumberOfScales.");
    return FAILED;
  }
  this->LastSigma = std::numeric_limits<double>::quiet_NaN();
  double sigma = this->Sigma;
  if (this->SigmaMode == SIGMA_RELATIVE && !this->RelativeSigma(run, sigma))
  {
    return ABORTED;
  }
  const auto feature =
    vtkGLSOutputPrecision::NewArray(vtkGLSArrayNames::Feature, run.Input->GetNumberOfPoints(), 1, this->OutputPrecision);
  if (!this->ComputeFeatureAndSummary(run, sigma, feature))
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

bool vtkGLSContinuousFeatures::ComputeFeatureAndSummary(vtkGLSRun& run, double sigma, vtkDataArray* featureArray)
{
  using vtkGLSOutputPrecision::ValuesOf;
  const int precision = this->OutputPrecision;
  const bool single = vtkGLSOutputPrecision::IsSingle(precision);
  const gls::FeatureMeasure measure = static_cast<gls::FeatureMeasure>(this->FeatureMeasure);
  const std::vector<double>& t = run.Scales;
  const vtkIdType n = run.Input->GetNumberOfPoints();
  if (!this->ScaleSummary)
  {
    std::vector<double> narrowed(single ? static_cast<std::size_t>(n) : 0);
    double* feature = single ? narrowed.data() : ValuesOf<double>(featureArray);
    const bool completed = this->ReduceVariation(
      run,
      [sigma, measure, &t](const double* nu) {
        return gls::continuousFeature(nu, t.data(), static_cast<int>(t.size()), sigma, measure);
      },
      feature, 1.0);
    std::copy(narrowed.begin(), narrowed.end(), ValuesOf<float>(featureArray));
    return completed;
  }
  // The summary's arrays, filled by the fused pass in the output type (Real).
  const auto summarize = [&](auto zero) {
    using Real = decltype(zero);
    vtkNew<vtkIntArray> count;
    count->SetName(vtkGLSArrayNames::PertinentScaleCount);
    count->SetNumberOfTuples(n);
    const auto stableScale = vtkGLSOutputPrecision::NewArray(vtkGLSArrayNames::StableScale, n, 1, precision);
    const auto tau = vtkGLSOutputPrecision::NewArray(vtkGLSArrayNames::StableTau, n, 1, precision);
    const auto kappa = vtkGLSOutputPrecision::NewArray(vtkGLSArrayNames::StableKappa, n, 1, precision);
    const auto phi = vtkGLSOutputPrecision::NewArray(vtkGLSArrayNames::StablePhi, n, 1, precision);
    const auto maxNu = vtkGLSOutputPrecision::NewArray(vtkGLSArrayNames::MaxVariation, n, 1, precision);
    const auto maxNuScale = vtkGLSOutputPrecision::NewArray(vtkGLSArrayNames::MaxVariationScale, n, 1, precision);
    typename gls::ScaleSummarySinkT<Real>::Outputs out;
    out.feature = ValuesOf<Real>(featureArray);
    out.pertinentCount = count->GetPointer(0);
    out.stableScale = ValuesOf<Real>(stableScale);
    out.tau = ValuesOf<Real>(tau);
    out.kappa = ValuesOf<Real>(kappa);
    out.phi = ValuesOf<Real>(phi);
    out.maxVariation = ValuesOf<Real>(maxNu);
    out.maxVariationScale = ValuesOf<Real>(maxNuScale);
    gls::ScaleSummarySinkT<Real> sink(
      t, gls::resolveThreadCount(this->NumberOfThreads), this->Weights(), sigma, measure, out);
    // DirectionSummary: the steadiest principal directions from the same fit, beside the summary.
    using namespace vtkGLSSteadiestDirections;
    const auto steadiest = this->DirectionSummary ? NewArrays(kSteadiestArrays, n, precision)
                                                  : std::vector<vtkSmartPointer<vtkDataArray>>();
    const bool completed = !this->DirectionSummary
      ? this->FeedSamples(run, sink, nullptr, 0.05, 1.0)
      : WithSink(precision, t, this->AnisotropyThreshold, -1, steadiest, {}, [&](gls::ScaleSampleSink& directions) {
          gls::SinkPair both(sink, directions);
          return this->FeedSamples(run, both, nullptr, 0.05, 1.0);
        });
    if (!completed)
    {
      return false;
    }
    vtkPointData* pd = run.Output->GetPointData();
    pd->AddArray(count);
    for (vtkDataArray* array : { stableScale.Get(), tau.Get(), kappa.Get(), phi.Get(), maxNu.Get(), maxNuScale.Get() })
    {
      pd->AddArray(array);
    }
    vtkGLSSteadiestDirections::AddTo(pd, steadiest, false); // GLSFeature stays the active scalars
    return true;
  };
  return single ? summarize(0.0f) : summarize(0.0);
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

void vtkGLSContinuousFeatures::DescribeSettings(std::vector<SettingRange>& settings)
{
  this->Superclass::DescribeSettings(settings);
  settings.push_back({ "SigmaMode", static_cast<double>(this->SigmaMode), static_cast<double>(SIGMA_ABSOLUTE), static_cast<double>(SIGMA_RELATIVE) });
  settings.push_back({ "FeatureMeasure", static_cast<double>(this->FeatureMeasure), static_cast<double>(SCALE), static_cast<double>(LOG_SCALE) });
  settings.push_back({ "OutputPrecision", static_cast<double>(this->OutputPrecision),
    static_cast<double>(vtkAlgorithm::SINGLE_PRECISION), static_cast<double>(vtkAlgorithm::DOUBLE_PRECISION) });
  settings.push_back({ "AnisotropyThreshold", this->AnisotropyThreshold, 0.01, 1.0 });
}

void vtkGLSContinuousFeatures::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ReuseInputScaleSpace: " << this->ReuseInputScaleSpace << "\n";
  os << indent << "ScaleSummary: " << this->ScaleSummary << "\n";
  os << indent << "DirectionSummary: " << this->DirectionSummary << "\n";
  os << indent << "AnisotropyThreshold: " << this->AnisotropyThreshold << "\n";
  os << indent << "SigmaMode: " << (this->SigmaMode == SIGMA_RELATIVE ? "Relative" : "Absolute") << "\n";
  os << indent << "Sigma: " << this->Sigma << "\n";
  os << indent << "TargetMedianFeature: " << this->TargetMedianFeature << "\n";
  os << indent << "FeatureMeasure: " << (this->FeatureMeasure == SCALE ? "Scale" : "LogScale") << "\n";
  os << indent << "OutputPrecision: " << vtkGLSOutputPrecision::Name(this->OutputPrecision) << "\n";
}
