#include "gls/AdaptiveBandwidth.h"

#include "gls/NeighborGrid.h"
#include "gls/Numeric.h"
#include "gls/WeightedSums.h"

#include <cmath>
#include <vector>

namespace gls
{

double rawBandwidth(const double* nu, const double* scales, int count, double threshold)
{
  if (count < 1 || !isFinite(nu[count - 1]))
  {
    return quietNaN<double>();
  }
  for (int k = count - 2; k >= 0; --k)
  {
    if (!isFinite(nu[k]))
    {
      return scales[k + 1];
    }
    const double slope = -(nu[k + 1] - nu[k]) / std::log(scales[k + 1] / scales[k]);
    if (slope > threshold)
    {
      return scales[k + 1];
    }
  }
  return scales[0];
}

bool smoothBandwidth(const double* xyz, std::size_t n, const double* raw, double radius,
  const ParallelOptions& parallel, double* out)
{
  if (!(radius > 0.0))
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      out[i] = raw[i];
    }
    return true;
  }
  std::vector<unsigned char> admit(n, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    admit[i] = isFinite(raw[i]) ? 1 : 0;
  }
  NeighborGrid grid;
  grid.setThreads(parallel.threads);
  grid.build(xyz, nullptr, n, radius, admit.data());
  const GridView& g = grid.view();
  return parallelFor(n, parallel, [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t i = begin; i < end; ++i)
    {
      const Vec3 p{ xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] };
      if (!isFinite(p.x) || !isFinite(p.y) || !isFinite(p.z))
      {
        out[i] = quietNaN<double>();
        continue;
      }
      double sw = 0.0, swb = 0.0;
      forEachInBall(g, p, radius, [&](std::uint64_t j, const Vec3&, double d2) {
        const double w = weightAt(d2, radius);
        sw += w;
        swb += w * raw[g.ids[j]];
      });
      out[i] = sw > 0.0 ? swb / sw : quietNaN<double>();
    }
  });
}

} // namespace gls
