// A ScaleSampleSink that turns each point's samples into its raw adaptive bandwidth on the fly (nu lives in a
// per-thread buffer only): memory O(N), not O(N x scales).
#pragma once

#include "gls/AdaptiveBandwidth.h"
#include "gls/Descriptors.h"
#include "gls/ScaleSpaceEngine.h"

#include <vector>

namespace gls
{

class BandwidthSink : public ScaleSampleSink
{
public:
  /// scales: the engine's scales (kept by reference); raw: one output value per point (length).
  BandwidthSink(const std::vector<double>& scales, int threads, VariationWeights weights, double threshold,
    double* raw)
    : Scales(scales)
    , Weights(weights)
    , Threshold(threshold)
    , Raw(raw)
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
    this->Raw[id] = rawBandwidth(nu.data(), this->Scales.data(), static_cast<int>(this->Scales.size()),
      this->Threshold);
  }

private:
  const std::vector<double>& Scales;
  VariationWeights Weights;
  double Threshold;
  double* Raw;
  std::vector<std::vector<double>> Nu;
};

} // namespace gls
