#include "gls/MultiresolutionKernel.h"

#include "KernelBatches.h"

#include <cstring>

namespace gls
{
namespace
{

#if GLS_KERNEL_VECTORS
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
/// addSampleSums (AggregateMoments.h) with f = (f0, f1, f8): the same products and sums, element by element (fused
/// into multiply-adds in the AVX2 build).
GLS_ALWAYS_INLINE void addSums(AggregateMoments& a, kernel::Double4 f0, kernel::Double4 f1, double f8, double d2)
{
  using kernel::load4;
  using kernel::store4;
  const double d4 = d2 * d2;
  double* m = a.m;
  store4(m, load4(m) + f0);
  store4(m + 4, load4(m + 4) + f1);
  m[8] += f8;
  store4(m + 9, load4(m + 9) + d2 * f0);
  store4(m + 13, load4(m + 13) + d2 * f1);
  m[17] += d2 * f8;
  store4(m + 18, load4(m + 18) + d4 * f0);
  store4(m + 22, load4(m + 22) + d4 * f1);
  m[26] += d4 * f8;
}

GLS_ALWAYS_INLINE void addCellVectorized(AggregateMoments& a, const Vec3& x, double d2, const PyramidCell& c)
{
  const double m = c.count;
  const kernel::Double4 f0 = { m, m * x.x, m * x.y, m * x.z };
  const kernel::Double4 f1 = { c.normalSum.x, c.normalSum.y, c.normalSum.z, c.offsetDotNormal + dot(x, c.normalSum) };
  addSums(a, f0, f1, c.spread + m * d2, d2);
}

GLS_ALWAYS_INLINE void addPointVectorized(AggregateMoments& a, const Vec3& x, double d2, const Vec3& n)
{
  const kernel::Double4 f0 = { 1.0, x.x, x.y, x.z };
  const kernel::Double4 f1 = { n.x, n.y, n.z, dot(x, n) };
  addSums(a, f0, f1, d2, d2);
}
#pragma GCC diagnostic pop
#else
GLS_ALWAYS_INLINE void addCellVectorized(AggregateMoments& a, const Vec3& x, double d2, const PyramidCell& c)
{
  addCell(a, x, d2, c.count, c.normalSum, c.offsetDotNormal, c.spread);
}

GLS_ALWAYS_INLINE void addPointVectorized(AggregateMoments& a, const Vec3& x, double d2, const Vec3& n)
{
  addPoint(a, x, d2, n);
}
#endif

/// Adds the cells taken whole: their centroids inside the ball, binned by the centroid's distance.
GLS_ALWAYS_INLINE void addTakenCells(const MultiresolutionView& v, const Vec3& p, const ScaleBinning& b, double r2,
  const std::vector<std::uint32_t>& taken, AggregateMoments* bins)
{
  kernel::addInsideBall(
    p, b, r2, std::size_t(0), taken.size(), [&](std::size_t c) { return taken[c]; },
    [&](std::uint32_t i) -> const Vec3& { return v.cells[i].centroid; },
    [&](std::uint32_t i, double d2, int k) {
      const PyramidCell& cell = v.cells[i];
      addCellVectorized(bins[k], cell.centroid - p, d2, cell);
    });
}

/// Adds the points of the finest cells read one by one that lie inside the ball.
GLS_ALWAYS_INLINE void addReadPoints(const MultiresolutionView& v, const Vec3& p, const ScaleBinning& b, double r2,
  const std::vector<std::uint32_t>& read, AggregateMoments* bins)
{
  for (std::uint32_t cell : read)
  {
    kernel::addInsideBall(
      p, b, r2, v.nodes[cell].first, v.nodes[cell].last, [](std::uint32_t c) { return c; },
      [&](std::uint32_t i) -> const Vec3& { return v.points[i]; },
      [&](std::uint32_t i, double d2, int k) { addPointVectorized(bins[k], v.points[i] - p, d2, v.normals[i]); });
  }
}

/// The walk of a region (walkRegion): the cells taken whole (s.taken) and the finest cells read point by point
/// (s.read) for every point of the region, found level by level: each cell of the frontier is skipped (outside
/// every ball of the region), taken whole, read point by point (level 0) or opened (its children make the next
/// level's frontier); the writes only advance indices.
GLS_ALWAYS_INLINE void walk(const MultiresolutionView& v, const WalkRegion& region, double r, double smallest,
  MultiresolutionScratch& s)
{
  s.taken.clear();
  s.read.clear();
  s.frontier.clear();
  const double r2 = r * r;
  const double eps2 = v.accuracy * v.accuracy;
  const double floor2 = smallest * smallest;
  if (v.topEnd > v.topBegin && r > 0.0)
  {
    forEachTopCell(v, region, r, [&](std::uint32_t c) { s.frontier.push_back(c); });
  }
  for (int level = v.topLevel; level >= 0 && !s.frontier.empty(); --level)
  {
    const double edge = v.levelSize[level];
    const double edge2 = edge * edge;
    const std::size_t n = s.frontier.size();
    const std::size_t takenBefore = s.taken.size();
    s.taken.resize(takenBefore + n);
    s.opened.resize(n);
    std::size_t taken = takenBefore, opened = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
      const std::uint32_t c = s.frontier[i];
      const double box2 = squaredDistanceToCube(region, v.nodes[c].corner, edge);
      const bool inside = box2 < r2;
      const bool whole = takenWhole(edge2, box2, eps2, floor2);
      s.taken[taken] = c;
      taken += inside && whole ? 1 : 0;
      s.opened[opened] = c;
      opened += inside && !whole ? 1 : 0;
    }
    s.taken.resize(taken);
    if (level == 0)
    {
      s.read.assign(s.opened.begin(), s.opened.begin() + static_cast<long>(opened));
      break;
    }
    s.next.clear();
    for (std::size_t i = 0; i < opened; ++i)
    {
      const PyramidNode& node = v.nodes[s.opened[i]];
      for (std::uint32_t c = node.first; c < node.last; ++c)
      {
        s.next.push_back(c);
      }
    }
    s.frontier.swap(s.next);
  }
}

bool sameWalk(const WalkKey& a, const WalkKey& b)
{
  return a.nodes == b.nodes && a.count == b.count && a.accuracy == b.accuracy && a.radius == b.radius &&
    a.smallest == b.smallest && a.region.edge == b.region.edge && a.region.corner.x == b.region.corner.x &&
    a.region.corner.y == b.region.corner.y && a.region.corner.z == b.region.corner.z;
}

GLS_ALWAYS_INLINE void evaluate(const MultiresolutionView& v, const Vec3& p, const ScaleBinning& b,
  double minNeighbors, MultiresolutionScratch& s, ScaleSample* out)
{
  if (b.count <= 0)
  {
    return;
  }
  s.bins.resize(static_cast<std::size_t>(b.count));
  std::memset(static_cast<void*>(s.bins.data()), 0, sizeof(AggregateMoments) * s.bins.size()); // all 0.0
  const double r = b.scales[b.count - 1];
  const WalkKey key{ v.nodes, v.count, v.accuracy, r, b.scales[0], walkRegion(v, p) };
  if (!s.walked || !sameWalk(s.walkedKey, key))
  {
    walk(v, key.region, r, key.smallest, s);
    s.walked = true;
    s.walkedKey = key;
  }
  addTakenCells(v, p, b, r * r, s.taken, s.bins.data());
  addReadPoints(v, p, b, r * r, s.read, s.bins.data());
  fitAllScalesFromBins(b, minNeighbors, s.bins.data(), out);
}

void evaluateBaseline(const MultiresolutionView& v, const Vec3& p, const ScaleBinning& b, double minNeighbors,
  MultiresolutionScratch& s, ScaleSample* out)
{
  evaluate(v, p, b, minNeighbors, s, out);
}

#if GLS_KERNEL_DISPATCH
__attribute__((target("avx2,fma"))) void evaluateAvx2(const MultiresolutionView& v, const Vec3& p,
  const ScaleBinning& b, double minNeighbors, MultiresolutionScratch& s, ScaleSample* out)
{
  evaluate(v, p, b, minNeighbors, s, out);
}
#endif

} // namespace

void evaluateAllScalesMultiresolutionOnCpu(const MultiresolutionView& v, const Vec3& p, const ScaleBinning& b,
  double minNeighbors, MultiresolutionScratch& s, ScaleSample* out)
{
#if GLS_KERNEL_DISPATCH
  if (kernel::hasAvx2())
  {
    evaluateAvx2(v, p, b, minNeighbors, s, out);
    return;
  }
#endif
  evaluateBaseline(v, p, b, minNeighbors, s, out);
}

} // namespace gls
