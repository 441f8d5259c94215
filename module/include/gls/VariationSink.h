// A ScaleSampleSink that reduces each point's geometric variation nu over the scales to one value on the fly (nu
// lives in a per-thread buffer only): the fused path whose memory is O(N), not O(N x scales). The continuous
// feature and the adaptive bandwidth are such reductions.
#pragma once

#include "gls/Descriptors.h"
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

} // namespace gls
