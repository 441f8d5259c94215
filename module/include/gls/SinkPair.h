// Two sinks fed by one run of the engine (ScaleSpaceEngine.h): each point's principal curvatures and samples go to
// both, first then second, on the caller's thread. A filter that writes two reductions of the same fit (the continuous
// features and the steadiest principal directions) runs the fit once.
#pragma once

#include "gls/ScaleSpaceEngine.h"

namespace gls
{

class SinkPair : public ScaleSampleSink
{
public:
  SinkPair(ScaleSampleSink& first, ScaleSampleSink& second)
    : First(first)
    , Second(second)
  {
  }

  void consume(std::uint64_t id, const ScaleSample* samples, int thread) override
  {
    this->First.consume(id, samples, thread);
    this->Second.consume(id, samples, thread);
  }

  void consumeCurvatures(std::uint64_t id, const PrincipalCurvatures* curvatures, int thread) override
  {
    this->First.consumeCurvatures(id, curvatures, thread);
    this->Second.consumeCurvatures(id, curvatures, thread);
  }

private:
  ScaleSampleSink& First;
  ScaleSampleSink& Second;
};

} // namespace gls
