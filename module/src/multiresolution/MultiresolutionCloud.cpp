#include "gls/MultiresolutionCloud.h"

#include "gls/KeySort.h"
#include "gls/MultiresolutionCellSums.h"
#include "gls/MultiresolutionTakeWhole.h"
#include "gls/NeighborGrid.h"
#include "gls/Numeric.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gls
{
namespace
{

/// Below this many keys, runsOfEqualKeys takes one thread.
constexpr std::size_t kParallelRuns = 65536;

constexpr double kLatticeCells = static_cast<double>(std::uint64_t(1) << kMortonBits);

/// Inverse of spreadMortonBits: gathers every third bit into the low 21 bits.
std::uint64_t compactMortonBits(std::uint64_t v)
{
  v &= 0x1249249249249249ULL;
  v = (v | (v >> 2)) & 0x10c30c30c30c30c3ULL;
  v = (v | (v >> 4)) & 0x100f00f00f00f00fULL;
  v = (v | (v >> 8)) & 0x1f0000ff0000ffULL;
  v = (v | (v >> 16)) & 0x1f00000000ffffULL;
  v = (v | (v >> 32)) & 0x1fffffULL;
  return v;
}

std::uint64_t latticeCoordinate(double v, double origin, double edge)
{
  const double c = std::floor((v - origin) / edge);
  if (!(c >= 0.0))
  {
    return 0;
  }
  return c >= kLatticeCells - 1.0 ? static_cast<std::uint64_t>(kLatticeCells - 1.0) : static_cast<std::uint64_t>(c);
}

/// The key of the finest lattice's cell (edge h0, lowest corner `origin`) that holds q.
std::uint64_t finestLatticeKey(const double* q, const Vec3& origin, double h0)
{
  return mortonKey(latticeCoordinate(q[0], origin.x, h0), latticeCoordinate(q[1], origin.y, h0),
    latticeCoordinate(q[2], origin.z, h0));
}

/// The runs of equal keyOf(k) over k in [0, n) (keyOf non-decreasing): each run's key and first index, with n
/// appended to the first indices. On up to `threads` threads, each counting then writing the runs that begin in its
/// slice, so the result does not depend on the thread count.
template <typename KeyOf>
void runsOfEqualKeys(std::size_t n, const KeyOf& keyOf, int threads, UninitializedArray<std::uint64_t>& runKeys,
  UninitializedArray<std::uint64_t>& runStarts)
{
  const std::size_t slices = n < kParallelRuns ? 1 : static_cast<std::size_t>(std::max(threads, 1));
  const auto sliceBegin = [n, slices](std::size_t s) { return n * s / slices; };
  const auto begins = [&keyOf](std::size_t k) { return k == 0 || keyOf(k) != keyOf(k - 1); };
  ParallelOptions bySlice;
  bySlice.threads = static_cast<int>(slices);
  bySlice.chunk = 1;
  std::vector<std::size_t> first(slices + 1, 0); // runs beginning in the slices before
  parallelFor(slices, bySlice, [&](std::size_t s, std::size_t, int) {
    std::size_t count = 0;
    for (std::size_t k = sliceBegin(s); k < sliceBegin(s + 1); ++k)
    {
      count += begins(k) ? 1 : 0;
    }
    first[s + 1] = count;
  });
  for (std::size_t s = 0; s < slices; ++s)
  {
    first[s + 1] += first[s];
  }
  runKeys.resize(first[slices]);
  runStarts.resize(first[slices] + 1);
  parallelFor(slices, bySlice, [&](std::size_t s, std::size_t, int) {
    std::size_t r = first[s];
    for (std::size_t k = sliceBegin(s); k < sliceBegin(s + 1); ++k)
    {
      if (begins(k))
      {
        runKeys[r] = keyOf(k);
        runStarts[r++] = k;
      }
    }
  });
  runStarts[first[slices]] = n;
}

/// The options of one step of a build: progress mapped to [begin, end] of the caller's, chunks of 4096.
ParallelOptions buildStage(const ParallelOptions& parallel, double begin, double end)
{
  ParallelOptions o = progressStage(parallel, begin, end);
  o.chunk = 4096;
  return o;
}

/// Whether the caller's progress callback, told `fraction`, asks to abort.
bool aborted(const ParallelOptions& parallel, double fraction)
{
  return parallel.progress && parallel.progress(fraction);
}

/// The top level of a layout: the first whose cells are at least twice the largest scale (or the lattice's last).
int topLevelOf(const PyramidLayout& layout)
{
  int topLevel = 0;
  while (topLevel < kMortonBits - 1 && std::ldexp(layout.finestCellSize, topLevel) < 2.0 * layout.largestScale)
  {
    ++topLevel;
  }
  return topLevel;
}

/// The keys of the admitted points on the finest lattice, with their indices (the k-th admitted point: k itself
/// where all are), unsorted; false when the progress callback asked to abort.
bool finestKeys(const double* xyz, std::size_t n, const unsigned char* admit, const Vec3& origin, double h0,
  const ParallelOptions& stage, KeyedIndices& keyed)
{
  std::size_t admittedCount = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    admittedCount += admit[i] ? 1 : 0;
  }
  std::vector<std::uint64_t> admitted;
  if (admittedCount < n)
  {
    admitted.reserve(admittedCount);
    for (std::size_t i = 0; i < n; ++i)
    {
      if (admit[i])
      {
        admitted.push_back(i);
      }
    }
  }
  keyed.resize(admittedCount);
  return parallelFor(admittedCount, stage, [&](std::size_t b, std::size_t e, int) {
    for (std::size_t k = b; k < e; ++k)
    {
      const std::uint64_t i = admitted.empty() ? k : admitted[k];
      keyed[k] = { finestLatticeKey(xyz + 3 * i, origin, h0), i };
    }
  });
}

} // namespace

double nearCellEdge(double accuracy, double smallestScale)
{
  // The walks' eps2 and floor2 (v.accuracy and the smallest scale squared), so the limit is theirs bit for bit.
  const double limit2 = squaredNearCellLimit(accuracy * accuracy, smallestScale * smallestScale);
  if (!(limit2 > 0.0) || !isFinite(limit2))
  {
    return 0.0;
  }
  const double limit = std::sqrt(limit2);
  double edge = 0.0;
  for (const double mantissa : { 1.0, 1.25, 1.5, 1.75 })
  {
    double e = mantissa * std::exp2(std::floor(std::log2(limit / mantissa)));
    while (e * e > limit2)
    {
      e *= 0.5; // log2's rounding
    }
    edge = std::max(edge, e);
  }
  return edge;
}

PyramidLayout choosePyramidLayout(const double low[3], const double high[3], double spacing, double smallestScale,
  double largestScale, double accuracy)
{
  PyramidLayout layout;
  double extent = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    extent = std::max(extent, high[a] - low[a]);
  }
  if (!isFinite(extent))
  {
    extent = 0.0;
  }
  // Finest cells of about two spacings (measured on a 160k-point surface at Accuracy 0.2: 17.8 us per point, against
  // 19.1 us at one spacing, where most finest cells hold one point), scaled with the smallest scale: h0 in (spacing,
  // 2 spacing] is the near cells' edge (nearCellEdge) divided by a power of two.
  double h = 0.0;
  if (spacing > 0.0 && isFinite(spacing))
  {
    const double nearEdge = nearCellEdge(accuracy, smallestScale);
    h = nearEdge > 0.0 ? nearEdge * std::exp2(-std::ceil(std::log2(nearEdge / (2.0 * spacing))))
                       : std::exp2(std::floor(std::log2(2.0 * spacing)));
  }
  if (!(h > 0.0) || !isFinite(h))
  {
    h = extent > 0.0 ? std::exp2(std::ceil(std::log2(extent / (0.5 * kLatticeCells)))) : 1.0;
  }
  // The box fits in half the lattice's 2^21 cells (the lattice starts at its low corner).
  while (extent / h >= 0.5 * kLatticeCells && isFinite(h))
  {
    h *= 2.0;
  }
  layout.finestCellSize = h;
  // Walks shared by cubes of 4 finest cells per axis (about 16-30 points on a surface), or smaller ones where that
  // exceeds the smallest scale. Measured (bunny, 2 threads, us per point, one walk per point / per region):
  // 0.3M points 22.9 / 16.3, 3M points 26.4 / 16.5 (cubes of 8 cells: 17.2, of 16: 21.2: the walks read more cells).
  // Cubes of 8 cells where those are at most half the smallest scale (kFarRegionLevel: their own far regions).
  layout.walkLevel = 0;
  while (layout.walkLevel < 2 && std::ldexp(h, layout.walkLevel + 1) <= smallestScale)
  {
    ++layout.walkLevel;
  }
  if (layout.walkLevel == 2 && std::ldexp(h, kFarRegionLevel + 1) <= smallestScale)
  {
    layout.walkLevel = kFarRegionLevel;
  }
  layout.largestScale = largestScale;
  layout.low = { low[0], low[1], low[2] };
  layout.accuracy = accuracy;
  return layout;
}

std::uint64_t MultiresolutionCloud::finestKey(const Vec3& p) const
{
  const double q[3] = { p.x, p.y, p.z };
  return finestLatticeKey(q, this->View.origin, this->View.levelSize[0]);
}

bool MultiresolutionCloud::build(const double* xyz, const double* normals, std::size_t n,
  const unsigned char* admit, const PyramidLayout& layout, const ParallelOptions& parallel,
  const std::function<void()>& inputsCopied)
{
  *this = MultiresolutionCloud();
  const int threads = resolveThreadCount(parallel.threads);
  // Progress: the keys and the sort are the first 60%, the levels the rest.
  const int topLevel = topLevelOf(layout);
  const double h0 = layout.finestCellSize;
  const Vec3 origin = layout.low; // the lattice moves with the data: a shifted cloud gets the same cells
  KeyedIndices keyed;
  if (!finestKeys(xyz, n, admit, origin, h0, buildStage(parallel, 0.0, 0.1), keyed))
  {
    return this->fail();
  }
  sortByKey(keyed, threads);
  if (aborted(parallel, 0.5) ||
    !this->copySortedPoints(keyed, xyz, normals, sortedStorage(xyz, normals, n, admit, layout, threads),
      buildStage(parallel, 0.5, 0.55)))
  {
    return this->fail();
  }
  this->View.points = this->storedPoints(); // the lowest summed level's sums read them
  if (inputsCopied)
  {
    inputsCopied();
  }
  UninitializedArray<std::uint64_t> keys;   // the current level's cell keys
  UninitializedArray<std::uint64_t> starts; // the current level's cells: [starts[c], starts[c + 1]) of the level below
  runsOfEqualKeys(keyed.size(), [&keyed](std::size_t k) { return keyed[k].key; }, threads, keys, starts);
  KeyedIndices().swap(keyed);
  if (aborted(parallel, 0.6))
  {
    return this->fail();
  }
  this->reserveLevels(keys, topLevel);
  // Level by level, finest first.
  std::size_t below = 0; // index of the level below's first node in Nodes
  for (int level = 0; level <= topLevel; ++level)
  {
    const std::size_t first = this->Nodes.size();
    const ParallelOptions stage =
      buildStage(parallel, 0.6 + 0.4 * level / (topLevel + 1.0), 0.6 + 0.4 * (level + 1.0) / (topLevel + 1.0));
    if (!this->buildLevel(level, keys, starts, below, origin, h0, stage))
    {
      return this->fail();
    }
    if (level == topLevel)
    {
      this->TopKeys.assign(keys.begin(), keys.end());
      break;
    }
    // The next level's cells: runs of equal parent keys.
    UninitializedArray<std::uint64_t> parentKeys, parentStarts;
    runsOfEqualKeys(keys.size(), [&keys](std::size_t c) { return keys[c] >> 3; }, threads, parentKeys, parentStarts);
    keys.swap(parentKeys);
    starts.swap(parentStarts);
    below = first;
  }
  this->fillView(layout, topLevel, origin);
  return true;
}

bool MultiresolutionCloud::fail()
{
  *this = MultiresolutionCloud();
  return false;
}

bool MultiresolutionCloud::copySortedPoints(const KeyedIndices& keyed, const double* xyz, const double* normals,
  const SortedStorage& storage, const ParallelOptions& stage)
{
  const std::size_t m = keyed.size();
  const bool singlePoints = storage.singlePoints;
  const bool singleNormals = storage.singleNormals;
  if (singlePoints)
  {
    this->Points32.resize(3 * m);
  }
  else
  {
    this->Points.resize(m);
  }
  if (singleNormals)
  {
    this->Normals32.resize(3 * m);
  }
  else
  {
    this->Normals.resize(m);
  }
  this->Ids.resize(m);
  return parallelFor(m, stage, [&](std::size_t b, std::size_t e, int) {
    for (std::size_t k = b; k < e; ++k)
    {
      const std::uint64_t i = keyed[k].index;
      for (int a = 0; a < 3 && singlePoints; ++a)
      {
        this->Points32[3 * k + a] = static_cast<float>(xyz[3 * i + a]);
      }
      if (!singlePoints)
      {
        this->Points[k] = { xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] };
      }
      for (int a = 0; a < 3 && singleNormals; ++a)
      {
        this->Normals32[3 * k + a] = static_cast<float>(normals[3 * i + a]); // normalized when read
      }
      if (!singleNormals)
      {
        double u[3];
        unitNormal(normals + 3 * i, u);
        this->Normals[k] = { u[0], u[1], u[2] };
      }
      this->Ids[k] = static_cast<std::uint32_t>(i);
    }
  });
}

StoredPoints MultiresolutionCloud::storedPoints() const
{
  StoredPoints s;
  s.positions = this->Points.empty() ? nullptr : this->Points.data();
  s.positions32 = this->Points32.empty() ? nullptr : this->Points32.data();
  s.normals = this->Normals.empty() ? nullptr : this->Normals.data();
  s.normals32 = this->Normals32.empty() ? nullptr : this->Normals32.data();
  return s;
}

SortedStorage MultiresolutionCloud::sortedStorage(const double* xyz, const double* normals, std::size_t n,
  const unsigned char* admit, const PyramidLayout& layout, int threads, bool savingToo)
{
  SortedStorage s;
  s.singlePoints = layout.singleWhereExact && admittedAreFloatExact(xyz, n, admit, threads);
  s.normalsAreFloats = (layout.compactNormals || savingToo) && admittedAreFloatExact(normals, n, admit, threads);
  s.singleNormals = layout.compactNormals && s.normalsAreFloats;
  return s;
}

template <typename Key>
PyramidCounts MultiresolutionCloud::countLevels(std::size_t count, const Key& key, int topLevel)
{
  // Every level's node count from the finest keys (a cell of level l is a run of equal key >> 3 l; two neighbouring
  // distinct keys fall in different cells up to the level of their highest differing bit).
  std::vector<std::size_t> levelCount(static_cast<std::size_t>(topLevel) + 1, 0);
  for (std::size_t c = 0; c < count; ++c)
  {
    const std::uint64_t differ = c == 0 ? ~std::uint64_t(0) : key(c) ^ key(c - 1);
    if (differ == 0)
    {
      continue; // the same finest cell
    }
    const int highest = 63 - __builtin_clzll(differ);
    ++levelCount[static_cast<std::size_t>(std::min(highest / 3, topLevel))];
  }
  for (int level = topLevel; level > 0; --level)
  {
    levelCount[static_cast<std::size_t>(level - 1)] += levelCount[static_cast<std::size_t>(level)];
  }
  PyramidCounts counts;
  counts.top = levelCount[static_cast<std::size_t>(topLevel)];
  for (int level = 0; level <= topLevel; ++level)
  {
    counts.nodes += levelCount[static_cast<std::size_t>(level)];
    counts.cells += level >= kFirstSummedLevel ? levelCount[static_cast<std::size_t>(level)] : 0;
  }
  return counts;
}

void MultiresolutionCloud::reserveLevels(const UninitializedArray<std::uint64_t>& finestKeys, int topLevel)
{
  // So that the nodes and the cells are allocated once.
  const PyramidCounts counts =
    countLevels(finestKeys.size(), [&finestKeys](std::size_t c) { return finestKeys[c]; }, topLevel);
  this->Nodes.reserve(counts.nodes);
  this->Cells.reserve(counts.cells);
}

PyramidCounts MultiresolutionCloud::count(
  const double* xyz, const unsigned char* admit, std::size_t n, const PyramidLayout& layout, int threads)
{
  const int topLevel = topLevelOf(layout);
  const double h0 = layout.finestCellSize;
  KeyedIndices keyed;
  ParallelOptions stage;
  stage.threads = threads;
  finestKeys(xyz, n, admit, layout.low, h0, stage, keyed);
  sortByKey(keyed, threads);
  return countLevels(keyed.size(), [&keyed](std::size_t c) { return keyed[c].key; }, topLevel);
}

bool MultiresolutionCloud::buildLevel(int level, const UninitializedArray<std::uint64_t>& keys,
  const UninitializedArray<std::uint64_t>& starts, std::size_t below, const Vec3& origin, double h0,
  const ParallelOptions& stage)
{
  const std::size_t first = this->Nodes.size();
  const std::size_t count = keys.size();
  this->Nodes.resize(first + count);
  const bool summed = level >= kFirstSummedLevel;
  if (level == kFirstSummedLevel)
  {
    this->SummedBegin = first;
  }
  const std::size_t firstCell = this->Cells.size();
  if (summed)
  {
    this->Cells.resize(firstCell + count);
  }
  const double edge = std::ldexp(h0, level);
  return parallelFor(count, stage, [&](std::size_t b, std::size_t e, int) {
    for (std::size_t c = b; c < e; ++c)
    {
      PyramidNode& node = this->Nodes[first + c];
      const std::uint64_t key = keys[c];
      node.cube = packCube(compactMortonBits(key), compactMortonBits(key >> 1), compactMortonBits(key >> 2));
      const Vec3 corner = nodeCorner(origin, node, edge);
      node.first = static_cast<std::uint32_t>(level == 0 ? starts[c] : below + starts[c]);
      node.last = static_cast<std::uint32_t>(level == 0 ? starts[c + 1] : below + starts[c + 1]);
      if (!summed)
      {
        continue;
      }
      formSummedCell<OrientedSphereMoments>(this->Nodes.data(), this->View.points, this->SummedBegin,
        kFirstSummedLevel, static_cast<std::uint32_t>(first + c), level, corner, this->Cells.data());
    }
  });
}

void MultiresolutionCloud::fillView(const PyramidLayout& layout, int topLevel, const Vec3& origin)
{
  const double h0 = layout.finestCellSize;
  MultiresolutionView& v = this->View;
  v.nodes = this->Nodes.data();
  v.cells = this->Cells.data();
  v.topKeys = this->TopKeys.data();
  v.summedBegin = this->SummedBegin;
  v.summedLevel = kFirstSummedLevel;
  v.topBegin = this->Nodes.size() - this->TopKeys.size();
  v.topEnd = this->Nodes.size();
  v.topLevel = topLevel;
  for (int l = 0; l <= kMaxPyramidLevels; ++l)
  {
    v.levelSize[l] = std::ldexp(h0, l);
  }
  v.origin = origin;
  v.accuracy = layout.accuracy;
  v.walkLevel = std::min(std::max(layout.walkLevel, 0), topLevel);
  // Far regions of twice the walk region's edge, at most kFarRegionLevel (about 27 points each on a surface at 10M
  // points: a linearized cell costs its region about 8 times what a packed cell costs a point), where their reach
  // stays within the largest ball.
  v.farLevel = std::min(std::min(v.walkLevel + 1, kFarRegionLevel), topLevel);
  v.linearizedDistance = layout.linearizedDistance;
  v.farLevelCount = 0;
  while (v.farLevelCount < kMaxFarLevels && v.farLevel + v.farLevelCount <= topLevel &&
    v.linearizedDistance * halfDiagonal(v.levelSize[v.farLevel + v.farLevelCount]) < layout.largestScale)
  {
    ++v.farLevelCount;
  }
  v.count = this->Ids.size();
}

} // namespace gls
