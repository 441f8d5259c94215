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
#endif

/// Adds the sums f = (f0, f1, f8) of a point at squared distance d2 (addSampleSums in AggregateMoments.h: the same
/// products and sums, element by element, fused into multiply-adds in the AVX2 build).
GLS_ALWAYS_INLINE void addPackedSums(AggregateMoments& a, const double* f, double d2)
{
#if GLS_KERNEL_VECTORS
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
#else
  addSampleSums(a, f, d2);
#endif
}

/// A cell's share of one shell (addCellShare in CellMoments.h, the same products and sums element by element).
GLS_ALWAYS_INLINE void addPackedCellShare(AggregateMoments& a, const CellSample& s, double m0, double m1, double m2)
{
#if GLS_KERNEL_VECTORS
  using kernel::load4;
  using kernel::store4;
  const kernel::Double4 f0 = load4(s.sums);
  const kernel::Double4 f1 = load4(s.sums + 4);
  const kernel::Double4 g0 = load4(s.gradient);
  const kernel::Double4 g1 = load4(s.gradient + 4);
  const double f8 = s.sums[8], g8 = s.gradient[8];
  const double g1m = 2.0 * m0, g2m = 4.0 * m1;
  double* m = a.m;
  store4(m, load4(m) + m0 * f0);
  store4(m + 4, load4(m + 4) + m0 * f1);
  m[8] += m0 * f8;
  store4(m + 9, load4(m + 9) + (m1 * f0 + g1m * g0));
  store4(m + 13, load4(m + 13) + (m1 * f1 + g1m * g1));
  m[17] += m1 * f8 + g1m * g8;
  store4(m + 18, load4(m + 18) + (m2 * f0 + g2m * g0));
  store4(m + 22, load4(m + 22) + (m2 * f1 + g2m * g1));
  m[26] += m2 * f8 + g2m * g8;
#else
  addCellShare(a, s, m0, m1, m2);
#endif
}

#if GLS_KERNEL_VECTORS
#pragma GCC diagnostic pop
#endif

/// The samples of a walk, packed once for every point of its region, about the region's corner o (x = q - o): the
/// points with their nine sums f = (1, x, n, x.n, |x|^2), the cells with their CellSample (direction from the
/// region's centre), so that a point adds them as they are and moves the bins from o to itself once (shiftBins)
/// instead of forming them for every sample.
void packWalk(const MultiresolutionView& v, const WalkRegion& region, MultiresolutionScratch& s)
{
  const Vec3 o = region.corner;
  const Vec3 anchor = regionCentre(region);
  s.packedCells.resize(s.taken.size());
  for (std::size_t k = 0; k < s.taken.size(); ++k)
  {
    PyramidCell cell;
    cellMoments(v, s.taken[k], s.takenLevel[k], cell);
    PackedCell& out = s.packedCells[k];
    out.centroid = cell.centroid;
    makeCellSample(cell, o, cell.centroid - anchor, out.sample);
  }
  std::size_t n = 0;
  for (std::uint32_t cell : s.read)
  {
    n += v.nodes[cell].last - v.nodes[cell].first;
  }
  s.packedPoints.resize(n);
  PackedPoint* out = s.packedPoints.data();
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

/// Adds the packed cells for p, in batches: the squared distances and the shells of both ends of each cell's spread
/// first (loads without a branch between them), then the cells within one shell (most of them: m0 = 1, m1 = the
/// mean, m2 = mean^2 + half^2 / 3, as forEachShellOfSpread gives them), then the others through
/// forEachShellOfSpread itself.
GLS_ALWAYS_INLINE void addPackedCells(
  const Vec3& p, const ScaleBinning& b, double r2, const std::vector<PackedCell>& cells, AggregateMoments* bins)
{
  constexpr int kCellBatch = 32;
  double mean[kCellBatch];
  int shell[kCellBatch];
  std::uint32_t single[kCellBatch], split[kCellBatch];
  const std::size_t n = cells.size();
  for (std::size_t c = 0; c < n; c += kCellBatch)
  {
    const int m = static_cast<int>(n - c < kCellBatch ? n - c : kCellBatch);
    for (int j = 0; j < m; ++j)
    {
      const PackedCell& cell = cells[c + j];
      mean[j] = squaredNorm(cell.centroid - p) + cell.sample.spreadPerPoint;
    }
    int singles = 0, splits = 0;
    for (int j = 0; j < m; ++j)
    {
      const double half = cells[c + j].sample.halfWidth;
      const double lo = mean[j] - half, hi = mean[j] + half;
      const int first = firstScaleHolding(b, lo > 0.0 ? lo : 0.0);
      const int last = hi < r2 ? firstScaleHolding(b, hi) : -1;
      shell[j] = first;
      single[singles] = static_cast<std::uint32_t>(j);
      singles += first == last ? 1 : 0;
      split[splits] = static_cast<std::uint32_t>(j);
      splits += first != last && lo < r2 ? 1 : 0;
    }
    for (int i = 0; i < singles; ++i)
    {
      const int j = static_cast<int>(single[i]);
      const CellSample& sample = cells[c + j].sample;
      addPackedCellShare(bins[shell[j]], sample, 1.0, mean[j],
        mean[j] * mean[j] + sample.halfWidth * sample.halfWidth * (1.0 / 3.0));
    }
    for (int i = 0; i < splits; ++i)
    {
      const CellSample& sample = cells[c + split[i]].sample;
      forEachShellOfSpread(b, r2, mean[split[i]], sample.halfWidth,
        [&](int k, double m0, double m1, double m2) { addPackedCellShare(bins[k], sample, m0, m1, m2); });
    }
  }
}

/// Adds the packed samples of p's ball: the cells, each spread over the shells it meets (addCellSample), and the
/// points inside it, binned by their distance from p.
GLS_ALWAYS_INLINE void addPackedSamples(const Vec3& p, const ScaleBinning& b, double r2,
  const MultiresolutionScratch& s, AggregateMoments* bins)
{
  addPackedCells(p, b, r2, s.packedCells, bins);
  const std::vector<PackedPoint>& points = s.packedPoints;
  kernel::addInsideBall(
    p, b, r2, std::size_t(0), points.size(), [](std::size_t c) { return c; },
    [&](std::size_t i) -> const Vec3& { return points[i].position; },
    [&](std::size_t i, double d2, int k) { addPackedSums(bins[k], points[i].sums, d2); });
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
  s.takenLevel.clear();
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
    s.takenLevel.resize(taken, level);
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
    packWalk(v, key.region, s);
    s.walked = true;
    s.walkedKey = key;
  }
  addPackedSamples(p, b, r * r, s, s.bins.data());
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
