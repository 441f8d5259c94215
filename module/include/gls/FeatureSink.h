// A ScaleSampleSink that turns each point's samples into its continuous feature f(p) on the fly (nu lives in a
// per-thread buffer only): the fused path whose memory is O(N), not O(N x scales).
#pragma once

#include "gls/Descriptors.h"
#include "gls/ScaleAnalysis.h"
#include "gls/ScaleSpaceEngine.h"

#include <vector>

namespace gls
{

class ContinuousFeatureSink : public ScaleSampleSink
{
public:
  /// scales: the engine's scales (kept by reference); feature: one output value per point.
  ContinuousFeatureSink(const std::vector<double>& scales, int threads, VariationWeights weights, double sigma,
    FeatureMeasure measure, double* feature)
    : Scales(scales)
    , Weights(weights)
    , Sigma(sigma)
    , Measure(measure)
    , Feature(feature)
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
    this->Feature[id] = continuousFeature(
      nu.data(), this->Scales.data(), static_cast<int>(this->Scales.size()), this->Sigma, this->Measure);
  }

private:
  const std::vector<double>& Scales;
  VariationWeights Weights;
  double Sigma;
  FeatureMeasure Measure;
  double* Feature;
  std::vector<std::vector<double>> Nu;
};

} // namespace gls
