// MultiresolutionCloud owns the arrays behind a MultiresolutionView: the admitted points sorted by their Morton key
// on a lattice of cubes of edge h0 (ties by original index, so the layout is deterministic), the cells of level 0
// (runs of equal keys) and of every coarser level up to cells at least as large as the ball of the largest scale,
// each with the exact sums of its points. Memory is O(N): the sorted points and at most as many cells as points.
// The levels are built on all threads, each cell by one thread, so the result does not depend on the thread count.
#pragma once

#include "gls/KeySort.h"
#include "gls/MultiresolutionFarRule.h"
#include "gls/ParallelFor.h"
#include "gls/StoredPoints.h"
#include "gls/UninitializedArray.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace gls
{

/// The finest level whose cells keep their sums (PyramidCell); the cells of finer levels, of about 1.5 and 3 points
/// each on a surface, form theirs from their points when a walk takes them whole.
constexpr int kFirstSummedLevel = 2;

/// The level of the finest far regions (FarRule) at its largest: cubes of 8 finest cells per axis, twice the walk
/// region's edge where the walk region has 4 (the usual case). Where 8 finest cells are at most half the smallest scale
/// (dense clouds: 10M points on the bundled meshes, about 30 points per cube) the walk regions take this level too
/// and are their own far regions: one walk, one packing and one far walk for every such cube, instead of a walk and
/// a packing for every quarter of it. Measured at 10M points (the core, 2 threads, one after the other): bunny 63.0
/// and 62.5 s before, 57.4 and 57.9 s after; rocker arm 58.2 against 52.1 s. Accuracy (3,000 points against exact, p99
/// of nu): bunny 0.0616 -> 0.0631, rocker arm 0.0685 -> 0.0702; at 1M points the layouts do not change.
constexpr int kFarRegionLevel = 3;

/// How a pyramid is laid out. Two pyramids built with the same layout over clouds that agree within the reach of
/// an evaluation point give that point the same samples (this is what makes distributed runs equal serial ones).
struct PyramidLayout
{
  double finestCellSize = 0.0; ///< h0 (length unit); must be > 0
  double largestScale = 0.0;   ///< the top level's cells are at least twice this (or the 2^21 lattice is full)
  Vec3 low{};                  ///< a corner below every point: the lattice's origin (the cells move with the data)
  double accuracy = kDefaultAccuracy; ///< a cell is one sample where edge <= accuracy * distance
  int walkLevel = 0;           ///< the points of one cube of this level share a walk (MultiresolutionView)
  double linearizedDistance = kLinearizedDistance; ///< where the far parts begin (MultiresolutionView, FarRule)
  /// Store the points as floats when every admitted coordinate is a float exactly (StoredPoints.h); false: always
  /// as doubles (the same samples, bit for bit: the tests' reference).
  bool singleWhereExact = true;
  /// Store the normals as given, in floats, when every admitted one is a float exactly, and normalize them when read
  /// (StoredPoints.h: the same samples, 12 bytes a point less, a longer pass); false: their unit normals in doubles.
  bool compactNormals = false;
};

/// The edge the near cells take (takenWhole: at most kNearAccuracyShare * accuracy * smallestScale): the largest
/// number m 2^k at or below that limit with m one of 1, 1.25, 1.5 and 1.75 (so at least 0.8 of the limit), or 0 where
/// the limit is not positive. Every level of the pyramid is this edge times a power of two, so the levels sit at
/// fixed fractions of the smallest scale whatever the cloud's units (with power-of-two edges the near cells fell
/// anywhere between half the limit and the limit: 0.21 of the smallest scale on the rocker arm, 0.24 on the bunny,
/// at epsilon 0.5), and a mantissa of at most three bits keeps the cubes' corners, edges and squared distances exact
/// in double precision, as powers of two do: every build (fused multiply-adds or not, CPU or CUDA) takes the same
/// cells, even where a rule holds with equality (at epsilon 0.5, a cube two edges away).
double nearCellEdge(double accuracy, double smallestScale);

/// The layout for a cloud whose admitted points lie in [low, high]: h0 in (spacing, 2 spacing] (`spacing`: the typical
/// distance between neighbouring points), nearCellEdge divided by a power of two (a power of two where that edge is
/// 0), enlarged until the lattice of 2^21 cells per axis covers the box; walks shared by cubes of up to 4 h0 no larger
/// than the smallest scale.
PyramidLayout choosePyramidLayout(const double low[3], const double high[3], double spacing, double smallestScale,
  double largestScale, double accuracy);

/// How a pyramid stores its sorted points (StoredPoints.h), decided once from its inputs and its layout: the
/// coordinates as floats where asked (singleWhereExact) and every admitted one is a float exactly; the normals as given,
/// in floats, where asked (compactNormals) and every admitted one is a float exactly.
struct SortedStorage
{
  bool singlePoints = false;
  bool singleNormals = false;
  /// Every admitted normal is a float exactly (known when asked for compact normals, or for the saving).
  bool normalsAreFloats = false;
  /// The bytes a point's sorted copies take (position, normal and id): 28 to 52.
  double bytesPerPoint() const
  {
    return (this->singlePoints ? 3.0 * sizeof(float) : 1.0 * sizeof(Vec3)) +
      (this->singleNormals ? 3.0 * sizeof(float) : 1.0 * sizeof(Vec3)) + sizeof(std::uint32_t);
  }
  /// What compact normals would save a point where they are not asked for: 12 bytes, or 0.
  double compactNormalsSaving() const
  {
    return this->normalsAreFloats && !this->singleNormals ? 3.0 * sizeof(float) : 0.0;
  }
};

/// How many nodes (PyramidNode) and cells with stored sums (PyramidCell, levels kFirstSummedLevel and above) a
/// pyramid has: what its memory grows with.
struct PyramidCounts
{
  std::size_t nodes = 0;
  std::size_t cells = 0;
  std::size_t top = 0; ///< the top level's nodes (whose keys the pyramid keeps too)
};

class MultiresolutionCloud
{
public:
  /// The counts of the pyramid that build() would make of these points, from their sorted finest keys (the build's
  /// first step: 0.65 s at 10M points where the whole build takes 2.2 s; 17 bytes a point while it runs), for a
  /// memory budget checked before the build.
  static PyramidCounts count(const double* xyz, const unsigned char* admit, std::size_t n, const PyramidLayout& layout,
    int threads);

  /// Builds the pyramid of the points with admit[i] != 0 (finite coordinates and normals that can be normalized
  /// required: admitOrientedPoints), their normals normalized by unitNormal. parallel.progress receives the fraction
  /// done; returns false if it asked to abort (the cloud is then empty). `inputsCopied`, when given, is called once
  /// xyz and normals are read for the last time (their sorted copies made, the levels not yet built).
  bool build(const double* xyz, const double* normals, std::size_t n, const unsigned char* admit,
    const PyramidLayout& layout, const ParallelOptions& parallel, const std::function<void()>& inputsCopied = nullptr);

  const MultiresolutionView& view() const { return this->View; }
  /// Moves out the original indices of the points in pyramid order (a locality-preserving evaluation order); the
  /// cloud holds none afterwards.
  UninitializedArray<std::uint32_t> takeIds() { return std::move(this->Ids); }
  /// The key of position p on the finest lattice: the pyramid lists its points by increasing key. A position outside
  /// the lattice takes the key of the nearest cell; a non-finite coordinate counts as the lattice's lowest.
  std::uint64_t finestKey(const Vec3& p) const;
  /// Nodes of every level (PyramidNode), and the cells with stored sums (levels kFirstSummedLevel and above).
  std::size_t nodeCount() const { return this->Nodes.size(); }
  std::size_t cellCount() const { return this->Cells.size(); }
  /// How build() will store these inputs' sorted points; `savingToo`: also whether the normals are floats where
  /// compact normals are not asked for (a scan of the normals the build itself does not need).
  static SortedStorage sortedStorage(const double* xyz, const double* normals, std::size_t n,
    const unsigned char* admit, const PyramidLayout& layout, int threads, bool savingToo = false);
  /// The bytes the pyramid's arrays hold (their capacity).
  double memoryBytes() const
  {
    return static_cast<double>(this->Points.capacity() + this->Normals.capacity()) * sizeof(Vec3) +
      static_cast<double>(this->Points32.capacity() + this->Normals32.capacity()) * sizeof(float) +
      static_cast<double>(this->Ids.capacity()) * sizeof(std::uint32_t) +
      static_cast<double>(this->TopKeys.capacity()) * sizeof(std::uint64_t) +
      static_cast<double>(this->Nodes.capacity()) * sizeof(PyramidNode) +
      static_cast<double>(this->Cells.capacity()) * sizeof(PyramidCell);
  }

private:
  /// Empties the cloud; returns false (a build's abort).
  bool fail();
  /// The points and normals (as floats or doubles: StoredPoints.h) and Ids in the order of the sorted keys.
  bool copySortedPoints(const KeyedIndices& keyed, const double* xyz, const double* normals,
    const SortedStorage& storage, const ParallelOptions& stage);
  /// The sorted points as the walks read them.
  StoredPoints storedPoints() const;
  /// Allocates Nodes and Cells once, for every level above these distinct finest keys up to topLevel.
  void reserveLevels(const UninitializedArray<std::uint64_t>& finestKeys, int topLevel);
  /// The counts of every level above `count` increasing finest keys key(c) (equal ones counted once) up to topLevel.
  template <typename Key>
  static PyramidCounts countLevels(std::size_t count, const Key& key, int topLevel);
  /// One level's nodes (cells with these keys, each the run [starts[c], starts[c + 1]) of the level below, whose
  /// first node is Nodes[below]) and, from kFirstSummedLevel up, their sums: from their points at that level, from
  /// their children above.
  bool buildLevel(int level, const UninitializedArray<std::uint64_t>& keys,
    const UninitializedArray<std::uint64_t>& starts, std::size_t below, const Vec3& origin, double h0,
    const ParallelOptions& stage);
  /// The view of the built levels.
  void fillView(const PyramidLayout& layout, int topLevel, const Vec3& origin);

  UninitializedArray<Vec3> Points;    ///< doubles, or empty when Points32 holds them
  UninitializedArray<Vec3> Normals;    ///< unit normals, or empty when Normals32 holds them
  UninitializedArray<float> Points32;  ///< 3 a point, or empty when Points holds them
  UninitializedArray<float> Normals32; ///< the normals as given, 3 a point (compactNormals)
  UninitializedArray<std::uint32_t> Ids; ///< original indices (below kMaxEnginePoints, as the nodes' point ranges)
  UninitializedArray<PyramidNode> Nodes;
  UninitializedArray<PyramidCell> Cells;
  std::vector<std::uint64_t> TopKeys;
  std::size_t SummedBegin = 0;
  MultiresolutionView View;
};

} // namespace gls
