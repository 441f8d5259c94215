#include "gls/StrayPoints.h"

#include "gls/NeighborGrid.h"
#include "gls/Numeric.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gls
{
namespace
{

constexpr std::size_t kStraySample = std::size_t(1) << 20;
constexpr std::size_t kFewestPoints = 100;

bool finitePosition(const double* p)
{
  return isFinite(p[0]) && isFinite(p[1]) && isFinite(p[2]);
}

/// The q-quantile of v (reordered in place).
double quantile(std::vector<double>& v, double q)
{
  const std::size_t k = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

} // namespace

std::size_t straySampleStride(std::size_t total)
{
  return std::max<std::size_t>(1, (total + kStraySample - 1) / kStraySample);
}

void appendStraySample(const double* xyz, std::size_t n, std::size_t stride, std::vector<double>& sample)
{
  for (std::size_t i = 0; i < n; i += stride)
  {
    if (finitePosition(xyz + 3 * i))
    {
      sample.insert(sample.end(), xyz + 3 * i, xyz + 3 * i + 3);
    }
  }
}

StrayBox strayBoxOfSample(std::vector<double>& sample, std::size_t finite)
{
  StrayBox box;
  const std::size_t count = sample.size() / 3;
  if (finite < kFewestPoints || count < kFewestPoints)
  {
    return box;
  }
  std::vector<double> v(count);
  for (int a = 0; a < 3; ++a)
  {
    for (std::size_t i = 0; i < count; ++i)
    {
      v[i] = sample[3 * i + static_cast<std::size_t>(a)];
    }
    box.low[a] = quantile(v, kStrayQuantile);
    box.high[a] = quantile(v, 1.0 - kStrayQuantile);
    box.extent = std::max(box.extent, box.high[a] - box.low[a]);
  }
  box.valid = box.extent > 0.0 && isFinite(box.extent);
  return box;
}

std::vector<std::uint64_t> strayCandidates(const double* xyz, std::size_t n, const StrayBox& box)
{
  std::vector<std::uint64_t> candidates;
  for (std::size_t i = 0; box.valid && i < n; ++i)
  {
    const double* p = xyz + 3 * i;
    if (!finitePosition(p))
    {
      continue;
    }
    bool outside = false;
    for (int a = 0; a < 3; ++a)
    {
      outside = outside || p[a] < box.low[a] - box.extent || p[a] > box.high[a] + box.extent;
    }
    if (outside)
    {
      candidates.push_back(i);
    }
  }
  return candidates;
}

std::vector<unsigned char> isolatedCandidates(const std::vector<double>& where, const StrayBox& box)
{
  const std::size_t count = where.size() / 3;
  std::vector<unsigned char> isolated(count, 0);
  if (count == 0)
  {
    return isolated;
  }
  const double radius = kStrayClusterRadius * box.extent;
  NeighborGrid grid;
  grid.build(where.data(), nullptr, count, radius);
  std::vector<std::pair<double, std::uint64_t>> nearest;
  for (std::size_t c = 0; c < count; ++c)
  {
    const Vec3 p{ where[3 * c], where[3 * c + 1], where[3 * c + 2] };
    grid.kNearest(p, kStrayClusterNeighbors + 1, nearest); // the point itself first
    int near = 0;
    for (const auto& q : nearest)
    {
      near += q.first <= radius * radius ? 1 : 0;
    }
    isolated[c] = near - 1 < kStrayClusterNeighbors ? 1 : 0;
  }
  return isolated;
}

std::vector<std::uint64_t> findStrayPoints(const double* xyz, std::size_t n)
{
  std::size_t finite = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    finite += finitePosition(xyz + 3 * i) ? 1 : 0;
  }
  std::vector<double> sample;
  appendStraySample(xyz, n, straySampleStride(n), sample);
  const StrayBox box = strayBoxOfSample(sample, finite);
  const std::vector<std::uint64_t> candidates = strayCandidates(xyz, n, box);
  std::vector<double> where;
  for (std::uint64_t i : candidates)
  {
    where.insert(where.end(), xyz + 3 * i, xyz + 3 * i + 3);
  }
  const std::vector<unsigned char> isolated = isolatedCandidates(where, box);
  std::vector<std::uint64_t> stray;
  for (std::size_t c = 0; c < candidates.size(); ++c)
  {
    if (isolated[c])
    {
      stray.push_back(candidates[c]);
    }
  }
  return stray;
}

} // namespace gls
