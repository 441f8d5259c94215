// libFuzzer target: the core's entry points on clouds, normals and scales decoded from arbitrary bytes (any double,
// NaN, infinities and huge values included): normal estimation (k nearest and radius, MST orientation), the
// one-pass scale space against the per-scale evaluation, and the per-point analyses. Invariants: no crash, hang or
// sanitizer report; a valid sample has finite values and phi > 0.
#include "gls/Descriptors.h"
#include "gls/NormalEstimation.h"
#include "gls/ScaleAnalysis.h"
#include "gls/ScaleSpaceEngine.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace
{

/// Reads doubles from the fuzz bytes, cycling; small well-formed values once the bytes run out.
class Decoder
{
public:
  Decoder(const std::uint8_t* data, std::size_t size)
    : Data(data)
    , Size(size)
  {
  }
  std::uint8_t byte() { return this->Size ? this->Data[this->Offset++ % this->Size] : 0; }
  double real()
  {
    if (this->Offset + 8 > this->Size)
    {
      return 0.01 * static_cast<double>(this->Counter++ % 97);
    }
    double v;
    std::memcpy(&v, this->Data + this->Offset, 8);
    this->Offset += 8;
    // Mostly ordinary magnitudes, sometimes the raw (possibly NaN or huge) value.
    return (this->byte() & 7) ? std::fmod(v, 10.0) : v;
  }

private:
  const std::uint8_t* Data;
  std::size_t Size;
  std::size_t Offset = 0;
  std::size_t Counter = 0;
};

struct Sink : gls::ScaleSampleSink
{
  std::vector<gls::ScaleSample> samples;
  std::size_t S = 0;
  void consume(std::uint64_t id, const gls::ScaleSample* s, int) override
  {
    std::copy(s, s + this->S, this->samples.begin() + static_cast<long>(id * this->S));
  }
};

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  Decoder in(data, size);
  const std::size_t n = 1 + in.byte() % 48;
  const int S = 1 + in.byte() % 6;
  std::vector<double> xyz(3 * n), nrm(3 * n);
  for (std::size_t i = 0; i < 3 * n; ++i)
  {
    xyz[i] = in.real();
    nrm[i] = in.real();
  }
  std::vector<double> scales;
  for (int k = 0; k < S; ++k)
  {
    const double t = std::abs(in.real());
    if (std::isfinite(t) && t > 0.0)
    {
      scales.push_back(t);
    }
  }
  std::sort(scales.begin(), scales.end());
  scales.erase(std::unique(scales.begin(), scales.end()), scales.end());
  if (scales.empty())
  {
    scales.push_back(1.0);
  }

  gls::NormalEstimationSettings ns;
  ns.k = 3 + in.byte() % 8;
  ns.neighborhood = (in.byte() & 1) ? gls::NeighborhoodType::Radius : gls::NeighborhoodType::KNearest;
  ns.radius = scales.back();
  ns.graphNeighbors = 1 + in.byte() % 6;
  ns.parallel.threads = 1;
  gls::NormalEstimationResult nr;
  gls::estimateNormals(xyz.data(), n, ns, nr);
  if (nr.normals.size() != 3 * n)
  {
    std::abort();
  }

  gls::ScaleSpaceSettings settings;
  settings.scales = scales;
  settings.minNeighbors = 1 + in.byte() % 6;
  settings.parallel.threads = 1;
  const double* normals = (in.byte() & 1) ? nr.normals.data() : nrm.data();
  gls::ScaleSpaceEngine engine(xyz.data(), normals, n, settings);
  settings.method = gls::EvaluationMethod::PerScale;
  gls::ScaleSpaceEngine reference(xyz.data(), normals, n, settings);
  Sink onePass, perScale;
  onePass.S = perScale.S = scales.size();
  onePass.samples.resize(n * scales.size());
  perScale.samples.resize(n * scales.size());
  engine.run(onePass);
  reference.run(perScale);
  std::vector<double> nu(scales.size()), pertinent(scales.size());
  for (std::size_t i = 0; i < n; ++i)
  {
    const gls::ScaleSample* s = onePass.samples.data() + i * scales.size();
    for (std::size_t k = 0; k < scales.size(); ++k)
    {
      if (s[k].valid && !(std::isfinite(s[k].tau) && std::isfinite(s[k].kappa) && s[k].phi > 0.0 &&
                          std::isfinite(s[k].dtau) && std::isfinite(s[k].dkappa)))
      {
        std::abort();
      }
      nu[k] = gls::geometricVariation(s[k], scales[k], {});
    }
    gls::pertinentScales(nu.data(), scales.data(), static_cast<int>(scales.size()), 3, pertinent.data());
    gls::continuousFeature(nu.data(), scales.data(), static_cast<int>(scales.size()), 0.1, gls::FeatureMeasure::LogScale);
  }
  std::string why;
  const std::vector<double> prior =
    gls::scalePrior(scales, gls::ScalePriorShape::LogGaussian, scales.front(), scales.back(), why);
  if (!prior.empty())
  {
    gls::multiScaleDissimilarity(onePass.samples.data(), onePass.samples.data() + (n - 1) * scales.size(), scales, prior);
  }
  return 0;
}
