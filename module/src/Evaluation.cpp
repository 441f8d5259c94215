#include "gls/Evaluation.h"

#include "gls/Numeric.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gls
{

BallCountEstimate estimateBallCount(const double* xyz, std::size_t count, std::size_t evaluated, double radius)
{
  BallCountEstimate e;
  const std::size_t maxNeighbors = 20000, maxSamples = 256;
  const auto finite = [&](std::size_t i) {
    return isFinite(xyz[3 * i]) && isFinite(xyz[3 * i + 1]) && isFinite(xyz[3 * i + 2]);
  };
  std::vector<std::size_t> neighbors;
  const std::size_t taken = std::min(count, maxNeighbors);
  for (std::size_t k = 0; k < taken; ++k)
  {
    const std::size_t i = count <= maxNeighbors ? k : k * count / maxNeighbors;
    if (finite(i))
    {
      neighbors.push_back(i);
    }
  }
  const double scaleUp = static_cast<double>(count) / static_cast<double>(std::max<std::size_t>(taken, 1));
  const double r2 = radius * radius;
  const std::size_t samples = std::min(evaluated, maxSamples);
  for (std::size_t k = 0; k < samples; ++k)
  {
    const std::size_t p = evaluated <= maxSamples ? k : k * evaluated / maxSamples;
    if (!finite(p))
    {
      continue;
    }
    double inside = 0.0;
    for (std::size_t i : neighbors)
    {
      const double dx = xyz[3 * i] - xyz[3 * p], dy = xyz[3 * i + 1] - xyz[3 * p + 1],
                   dz = xyz[3 * i + 2] - xyz[3 * p + 2];
      inside += dx * dx + dy * dy + dz * dz < r2 ? 1.0 : 0.0;
    }
    e.neighbors += inside * scaleUp;
    e.samples += 1.0;
  }
  return e;
}

} // namespace gls
