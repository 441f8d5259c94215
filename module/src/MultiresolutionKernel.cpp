#include "gls/MultiresolutionKernel.h"

#include "KernelBatches.h"

#include <cstring>

namespace gls
{
namespace
{

/// Adds the sums f = (f0, f1, f8) of a sample at squared distance d2 (addSampleSums in AggregateMoments.h: the same
/// products and sums, element by element, fused into multiply-adds in the AVX2 build).
GLS_ALWAYS_INLINE void addPackedSums(AggregateMoments& a, const double* f, double d2)
{
#if GLS_KERNEL_VECTORS
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
  using kernel::load4;
  using kernel::store4;
  const kernel::Double4 f0 = load4(f);
  const kernel::Double4 f1 = load4(f + 4);
  const double f8 = f[8];
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
#pragma GCC diagnostic pop
#else
  addSampleSums(a, f, d2);
#endif
}

/// The samples of a walk, packed once for every point of its region: each sample's position (a cell's centroid or a
/// point) and its nine sums f = (1, x, n, x.n, |x|^2) about the region's corner o (x = q - o), so that a point adds
/// them as they are and moves the bins from o to itself once (shiftBins) instead of forming f for every sample.
void packWalk(const MultiresolutionView& v, const Vec3& o, MultiresolutionScratch& s)
{
  std::size_t n = s.taken.size();
  for (std::uint32_t cell : s.read)
  {
    n += v.nodes[cell].last - v.nodes[cell].first;
  }
  s.packed.resize(n);
  PackedSample* out = s.packed.data();
  for (std::uint32_t i : s.taken)
  {
    const PyramidCell& c = v.cells[i];
    const Vec3 x = c.centroid - o;
    out->position = c.centroid;
    cellSums(x, squaredNorm(x), c.count, c.normalSum, c.offsetDotNormal, c.spread, out->sums);
    ++out;
  }
  for (std::uint32_t cell : s.read)
  {
    for (std::uint32_t i = v.nodes[cell].first; i < v.nodes[cell].last; ++i)
    {
      const Vec3 x = v.points[i] - o;
      out->position = v.points[i];
      pointSums(x, squaredNorm(x), v.normals[i], out->sums);
      ++out;
    }
  }
}

/// Adds the packed samples inside the ball of p, binned by their distance from p (cells: their centroid's).
GLS_ALWAYS_INLINE void addPackedSamples(
  const Vec3& p, const ScaleBinning& b, double r2, const std::vector<PackedSample>& packed, AggregateMoments* bins)
{
  kernel::addInsideBall(
    p, b, r2, std::size_t(0), packed.size(), [](std::size_t c) { return c; },
    [&](std::size_t i) -> const Vec3& { return packed[i].position; },
    [&](std::size_t i, double d2, int k) { addPackedSums(bins[k], packed[i].sums, d2); });
}

/// Moves the bins' sums from coordinates about o to coordinates about p (x_p = x_o + u, u = o - p): sum x gains
/// u sum 1, sum x.n gains u . sum n, sum |x|^2 gains 2 u . sum x + |u|^2 sum 1; the weights d^(2k) stay p's.
GLS_ALWAYS_INLINE void shiftBins(const Vec3& u, int count, AggregateMoments* bins)
{
  const double uu = squaredNorm(u);
  for (int k = 0; k < count; ++k)
  {
    for (int j = 0; j < 3; ++j)
    {
      double* f = bins[k].m + j * kAggregateValues;
      const double W = f[0];
      const Vec3 P{ f[1], f[2], f[3] };
      const Vec3 N{ f[4], f[5], f[6] };
      f[1] += u.x * W;
      f[2] += u.y * W;
      f[3] += u.z * W;
      f[7] += dot(u, N);
      f[8] += 2.0 * dot(u, P) + uu * W;
    }
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
    packWalk(v, key.region.corner, s);
    s.walked = true;
    s.walkedKey = key;
  }
  addPackedSamples(p, b, r * r, s.packed, s.bins.data());
  shiftBins(key.region.corner - p, b.count, s.bins.data());
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
