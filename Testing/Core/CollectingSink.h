// A ScaleSampleSink that keeps every sample (point-major), for tests.
#pragma once

#include "gls/ScaleSpaceEngine.h"

#include <cstring>
#include <vector>

namespace glstest
{

class CollectingSink : public gls::ScaleSampleSink
{
public:
  CollectingSink(std::size_t points, std::size_t scales)
    : Scales(scales)
    , Samples(points * scales)
  {
  }
  void consume(std::uint64_t id, const gls::ScaleSample* s, int) override
  {
    for (std::size_t k = 0; k < this->Scales; ++k)
    {
      this->Samples[id * this->Scales + k] = s[k];
    }
  }
  const gls::ScaleSample& at(std::size_t point, std::size_t scale) const
  {
    return this->Samples[point * this->Scales + scale];
  }
  std::size_t Scales;
  std::vector<gls::ScaleSample> Samples;
};

/// True when two samples hold the same bits in every value (the determinism tests).
inline bool sameBits(const gls::ScaleSample& a, const gls::ScaleSample& b)
{
  const double va[] = { a.tau, a.kappa, a.phi, a.dtau, a.dkappa, a.eta.x, a.eta.y, a.eta.z, a.deta.x, a.deta.y,
    a.deta.z, a.neighbors };
  const double vb[] = { b.tau, b.kappa, b.phi, b.dtau, b.dkappa, b.eta.x, b.eta.y, b.eta.z, b.deta.x, b.deta.y,
    b.deta.z, b.neighbors };
  return std::memcmp(va, vb, sizeof(va)) == 0;
}

/// Two per-point loops that must agree bit for bit: for every stride-th point i below count, first(i, out) and
/// second(i, out) each write S samples. The valid samples compared, or -1 when a sample's bits or validity differ.
template <typename First, typename Second>
long validSamplesIfSameBits(std::size_t count, std::size_t stride, std::size_t S, First&& first, Second&& second)
{
  std::vector<gls::ScaleSample> a(S), b(S);
  long valid = 0;
  for (std::size_t i = 0; i < count; i += stride)
  {
    first(i, a.data());
    second(i, b.data());
    for (std::size_t k = 0; k < S; ++k)
    {
      if (!sameBits(a[k], b[k]) || a[k].valid != b[k].valid)
      {
        return -1;
      }
      valid += a[k].valid ? 1 : 0;
    }
  }
  return valid;
}

/// Runs the engine over a cloud and returns every sample.
inline CollectingSink runScaleSpace(const std::vector<double>& points, const std::vector<double>& normals,
  const std::vector<double>& scales, int threads = 0, double minNeighbors = 6.0,
  gls::EvaluationMethod method = gls::EvaluationMethod::OnePass)
{
  gls::ScaleSpaceSettings settings;
  settings.scales = scales;
  settings.minNeighbors = minNeighbors;
  settings.parallel.threads = threads;
  settings.method = method;
  const std::size_t n = points.size() / 3;
  gls::ScaleSpaceEngine engine(points.data(), normals.data(), n, settings);
  CollectingSink sink(n, scales.size());
  engine.run(sink);
  return sink;
}

} // namespace glstest
