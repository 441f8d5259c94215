// A ScaleSampleSink that reduces each point's geometric variation nu over the scales to one value on the fly (nu
// lives in a per-thread buffer only): the fused path whose memory is O(N), not O(N x scales). The continuous
// feature and the adaptive bandwidth are such reductions.
#pragma once

#include "gls/Descriptors.h"
#include "gls/ScaleAnalysis.h"
#include "gls/ScaleSpaceEngine.h"

#include <functional>
#include <vector>

namespace gls
{

class VariationReductionSink : public ScaleSampleSink
{
public:
  /// Maps nu at the engine's scales (one value per scale) to the point's value. Called concurrently from several
  /// threads: it must only read shared state.
  using Reducer = std::function<double(const double* nu)>;

  /// scales: the engine's scales (kept by reference); out: one value per point.
  VariationReductionSink(
    const std::vector<double>& scales, int threads, VariationWeights weights, Reducer reduce, double* out)
    : Scales(scales)
    , Weights(weights)
    , Reduce(std::move(reduce))
    , Out(out)
    , Nu(static_cast<std::size_t>(threads), std::vector<double>(scales.size()))
  {
  }

  void consume(std::uint64_t id, const ScaleSample* s, int thread) override
  {
    std::vector<double>& nu = this->Nu[static_cast<std::size_t>(thread)];
    for (std::size_t k = 0; k < this->Scales.size(); ++k)
    {
      nu[k] = geometricVariation(s[k], this->Scales[k], this->Weights);
    }
    this->Out[id] = this->Reduce(nu.data());
  }

private:
  const std::vector<double>& Scales;
  VariationWeights Weights;
  Reducer Reduce;
  double* Out;
  std::vector<std::vector<double>> Nu;
};

/// The fused pass of the main job: per point, the continuous feature (as VariationReductionSink with
/// continuousFeature: the same bits) and the summary over the scales (summarizeScales), nothing per scale. Real: the
/// outputs' type (double, or float: each value rounded to nearest from its double, half the memory).
template <typename Real>
class ScaleSummarySinkT : public ScaleSampleSink
{
public:
  /// Where each point's values go (arrays of one value per point).
  struct Outputs
  {
    Real* feature = nullptr;
    int* pertinentCount = nullptr;
    Real* stableScale = nullptr;
    Real* tau = nullptr;
    Real* kappa = nullptr;
    Real* phi = nullptr;
    Real* maxVariation = nullptr;
    Real* maxVariationScale = nullptr;
  };

  /// scales: the engine's scales (kept by reference); sigma and measure: those of the feature.
  ScaleSummarySinkT(const std::vector<double>& scales, int threads, VariationWeights weights, double sigma,
    FeatureMeasure measure, const Outputs& out)
    : Scales(scales)
    , Weights(weights)
    , Sigma(sigma)
    , Measure(measure)
    , Out(out)
    , Nu(static_cast<std::size_t>(threads), std::vector<double>(scales.size()))
  {
  }

  void consume(std::uint64_t id, const ScaleSample* s, int thread) override
  {
    std::vector<double>& nu = this->Nu[static_cast<std::size_t>(thread)];
    const int count = static_cast<int>(this->Scales.size());
    for (int k = 0; k < count; ++k)
    {
      const std::size_t i = static_cast<std::size_t>(k);
      nu[i] = geometricVariation(s[k], this->Scales[i], this->Weights);
    }
    const ScaleSummary summary = summarizeScales(s, nu.data(), this->Scales.data(), count);
    this->Out.feature[id] =
      static_cast<Real>(continuousFeature(nu.data(), this->Scales.data(), count, this->Sigma, this->Measure));
    this->Out.pertinentCount[id] = summary.pertinentCount;
    this->Out.stableScale[id] = static_cast<Real>(summary.stableScale);
    this->Out.tau[id] = static_cast<Real>(summary.tau);
    this->Out.kappa[id] = static_cast<Real>(summary.kappa);
    this->Out.phi[id] = static_cast<Real>(summary.phi);
    this->Out.maxVariation[id] = static_cast<Real>(summary.maxVariation);
    this->Out.maxVariationScale[id] = static_cast<Real>(summary.maxVariationScale);
  }

private:
  const std::vector<double>& Scales;
  VariationWeights Weights;
  double Sigma;
  FeatureMeasure Measure;
  Outputs Out;
  std::vector<std::vector<double>> Nu;
};

using ScaleSummarySink = ScaleSummarySinkT<double>;

} // namespace gls
