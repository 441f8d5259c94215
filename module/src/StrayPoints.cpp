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

std::vector<std::uint64_t> findStrayPoints(const double* xyz, std::size_t n)
{
  std::size_t finite = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    finite += finitePosition(xyz + 3 * i) ? 1 : 0;
  }
  if (finite < kFewestPoints)
  {
    return {};
  }
  // The robust box from a regular sample of the finite points.
  const std::size_t stride = std::max<std::size_t>(1, (n + kStraySample - 1) / kStraySample);
  double low[3], high[3], extent = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    std::vector<double> v;
    for (std::size_t i = 0; i < n; i += stride)
    {
      if (finitePosition(xyz + 3 * i))
      {
        v.push_back(xyz[3 * i + a]);
      }
    }
    if (v.size() < kFewestPoints)
    {
      return {};
    }
    low[a] = quantile(v, kStrayQuantile);
    high[a] = quantile(v, 1.0 - kStrayQuantile);
    extent = std::max(extent, high[a] - low[a]);
  }
  if (!(extent > 0.0) || !isFinite(extent))
  {
    return {};
  }
  // The candidates: outside the box widened by its largest extent on every side.
  std::vector<std::uint64_t> candidates;
  std::vector<double> where;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double* p = xyz + 3 * i;
    if (!finitePosition(p))
    {
      continue;
    }
    bool outside = false;
    for (int a = 0; a < 3; ++a)
    {
      outside = outside || p[a] < low[a] - extent || p[a] > high[a] + extent;
    }
    if (outside)
    {
      candidates.push_back(i);
      where.insert(where.end(), p, p + 3);
    }
  }
  if (candidates.empty())
  {
    return {};
  }
  // Isolated: fewer than kStrayClusterNeighbors other candidates within the cluster radius.
  const double radius = kStrayClusterRadius * extent;
  NeighborGrid grid;
  grid.build(where.data(), nullptr, candidates.size(), radius);
  std::vector<std::pair<double, std::uint64_t>> nearest;
  std::vector<std::uint64_t> stray;
  for (std::size_t c = 0; c < candidates.size(); ++c)
  {
    const Vec3 p{ where[3 * c], where[3 * c + 1], where[3 * c + 2] };
    grid.kNearest(p, kStrayClusterNeighbors + 1, nearest); // the point itself first
    int near = 0;
    for (const auto& q : nearest)
    {
      near += q.first <= radius * radius ? 1 : 0;
    }
    if (near - 1 < kStrayClusterNeighbors)
    {
      stray.push_back(candidates[c]);
    }
  }
  return stray;
}

} // namespace gls
