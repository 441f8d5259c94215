// The multi-resolution pyramid as the evaluation reads it (docs/math.md, "Multi-resolution evaluation"), host/device:
// an octree of cubic cells (a pyramid of levels, cells of level l of edge h0 2^l, each with the exact sums of its
// points up to the second order, CellMoments.h) on a Morton-keyed lattice, and its geometry: the walk regions, the
// distances between cubes, the top cells a ball touches. Built by MultiresolutionCloud. The rest of the evaluation
// is in MultiresolutionTakeWhole.h (which cells are one sample), MultiresolutionFarRule.h (the far cells expanded
// once per region) and MultiresolutionReferenceWalk.h (the reference walk and evaluation of one point).
#pragma once

#include "gls/CellMoments.h"
#include "gls/Evaluation.h"
#include "gls/Numeric.h"
#include "gls/StoredPoints.h"

#include <cstdint>

namespace gls
{

constexpr int kMortonBits = 21;   ///< bits of a cell coordinate per axis in a 63-bit Morton key
constexpr int kMaxPyramidLevels = 21;

/// What the walk reads of a cell (16 bytes, apart from its sums, so that the walk touches few cache lines): its
/// cube, as its lattice coordinates (nodeCorner gives its lower corner), and its children.
struct PyramidNode
{
  std::uint64_t cube;        ///< the cube's lattice coordinates at its level, kMortonBits each: x, y, z from bit 0
  std::uint32_t first, last; ///< level > 0: its children, cells [first, last); level 0: its points [first, last)
};

/// The `cube` of a PyramidNode from the lattice coordinates of its level (each below 2^kMortonBits).
GLS_INLINE std::uint64_t packCube(std::uint64_t x, std::uint64_t y, std::uint64_t z)
{
  return x | (y << kMortonBits) | (z << (2 * kMortonBits));
}

/// Lower corner of a node's cube at a level of edge `edge` (length unit), origin the lattice's: origin + coordinate
/// times edge on each axis, exact (the lattice's edges have mantissas of at most three bits).
GLS_INLINE Vec3 nodeCorner(const Vec3& origin, const PyramidNode& node, double edge)
{
  const std::uint64_t mask = (std::uint64_t(1) << kMortonBits) - 1;
  return { origin.x + static_cast<double>(node.cube & mask) * edge,
    origin.y + static_cast<double>((node.cube >> kMortonBits) & mask) * edge,
    origin.z + static_cast<double>(node.cube >> (2 * kMortonBits)) * edge };
}

/// The pyramid as plain arrays (the same on the host and the device).
struct MultiresolutionView
{
  const PyramidNode* nodes = nullptr;  ///< all levels, finest first; the top level's cells are [topBegin, topEnd)
  /// The sums of the cells of levels summedLevel and above: node i's at cells[i - summedBegin]. The finer cells
  /// hold a few points each (about 1.5 and 3 on a surface): their sums are formed from their points when a walk
  /// takes them whole (cellMoments), which saves most of the pyramid's memory.
  const PyramidCell* cells = nullptr;
  std::uint64_t summedBegin = 0;       ///< index of the first node of level summedLevel
  int summedLevel = 0;
  const std::uint64_t* topKeys = nullptr; ///< Morton keys of the top level's cells, increasing
  std::uint64_t topBegin = 0, topEnd = 0;
  int topLevel = 0;                    ///< levels are 0 (finest) .. topLevel
  double levelSize[kMaxPyramidLevels + 1] = {}; ///< edge of a cell of each level
  Vec3 origin{};                       ///< lower corner of every level's cell (0, 0, 0)
  double accuracy = kDefaultAccuracy;  ///< a cell is one sample where edge <= accuracy * distance to its box
  int walkLevel = 0;                   ///< the points of one lattice cube of this level share one walk (walkRegion)
  /// The far parts of a walk (FarRule): the level of the finest far regions, how many levels of them, and where
  /// each begins, in half-diagonals of its region (0 or less: no far part).
  int farLevel = 0;
  int farLevelCount = 0;
  double linearizedDistance = 0.0;
  StoredPoints points;                 ///< the points and unit normals in pyramid order (a cell's are contiguous)
  std::uint64_t count = 0;
};

/// Spreads the low 21 bits of v to every third bit (the Morton interleave of one axis).
GLS_INLINE std::uint64_t spreadMortonBits(std::uint64_t v)
{
  v &= 0x1fffffULL;
  v = (v | (v << 32)) & 0x1f00000000ffffULL;
  v = (v | (v << 16)) & 0x1f0000ff0000ffULL;
  v = (v | (v << 8)) & 0x100f00f00f00f00fULL;
  v = (v | (v << 4)) & 0x10c30c30c30c30c3ULL;
  v = (v | (v << 2)) & 0x1249249249249249ULL;
  return v;
}

/// The Morton key of cell coordinates (i, j, k), each in [0, 2^21).
GLS_INLINE std::uint64_t mortonKey(std::uint64_t i, std::uint64_t j, std::uint64_t k)
{
  return spreadMortonBits(i) | (spreadMortonBits(j) << 1) | (spreadMortonBits(k) << 2);
}

/// The box a walk measures its distances from: the lattice cube of level walkLevel that holds p (or p itself,
/// edge 0, outside the lattice). Every point of one cube has the same walk, so the CPU kernel walks once per cube;
/// since the cube holds p, a distance from it is at most p's own distance and the walk's rules hold for p.
struct WalkRegion
{
  Vec3 corner; ///< lower corner (length unit)
  double edge; ///< edge (length unit; 0: the region is the point `corner`)
};

/// The lattice cube of level `level` that holds p, or p itself (edge 0) outside the lattice.
GLS_INLINE WalkRegion latticeCube(const MultiresolutionView& v, const Vec3& p, int level)
{
  const double edge = v.levelSize[level];
  const double cells = static_cast<double>(std::int64_t(1) << (kMortonBits - level));
  const double cx = roundDown((p.x - v.origin.x) / edge);
  const double cy = roundDown((p.y - v.origin.y) / edge);
  const double cz = roundDown((p.z - v.origin.z) / edge);
  if (!(edge > 0.0 && cx >= 0.0 && cx < cells && cy >= 0.0 && cy < cells && cz >= 0.0 && cz < cells))
  {
    return { p, 0.0 };
  }
  return { { v.origin.x + cx * edge, v.origin.y + cy * edge, v.origin.z + cz * edge }, edge };
}

GLS_INLINE WalkRegion walkRegion(const MultiresolutionView& v, const Vec3& p)
{
  return latticeCube(v, p, v.walkLevel);
}

/// The half-diagonal of a cube of edge `edge`: sqrt(3) / 2 times it.
GLS_INLINE double halfDiagonal(double edge)
{
  return 0.8660254037844386 * edge;
}

/// Distance between the intervals [lo1, hi1] and [lo2, hi2] (0 where they overlap): the larger of the two one-sided
/// gaps, at least 0 (at most one of them is positive). Written as selects of the larger value, which compile to
/// max instructions: the walks test every cell they visit, on either side of p's region at random, and a branch
/// per test mispredicted about half the time.
GLS_INLINE double gapBetweenIntervals(double lo1, double hi1, double lo2, double hi2)
{
  const double after = lo2 - hi1, before = lo1 - hi2;
  const double gap = after > before ? after : before;
  return gap > 0.0 ? gap : 0.0;
}

/// Squared distance from the region to the cube [corner, corner + edge]^3 (0 where they overlap): at most the
/// squared distance from any point of the region.
GLS_INLINE double squaredDistanceToCube(const WalkRegion& a, const Vec3& corner, double edge)
{
  const double dx = gapBetweenIntervals(a.corner.x, a.corner.x + a.edge, corner.x, corner.x + edge);
  const double dy = gapBetweenIntervals(a.corner.y, a.corner.y + a.edge, corner.y, corner.y + edge);
  const double dz = gapBetweenIntervals(a.corner.z, a.corner.z + a.edge, corner.z, corner.z + edge);
  return dx * dx + dy * dy + dz * dz;
}

/// Squared distance from the region to the farthest point of the cube [corner, corner + edge]^3: per axis, how far
/// the cube reaches past the region's interval.
GLS_INLINE double squaredDistanceToFarthestCorner(const WalkRegion& a, const Vec3& corner, double edge)
{
  const auto reach = [](double lo, double hi, double alo, double ahi) {
    const double below = alo - lo, above = hi - ahi;
    const double r = below > above ? below : above;
    return r > 0.0 ? r : 0.0;
  };
  const double dx = reach(corner.x, corner.x + edge, a.corner.x, a.corner.x + a.edge);
  const double dy = reach(corner.y, corner.y + edge, a.corner.y, a.corner.y + a.edge);
  const double dz = reach(corner.z, corner.z + edge, a.corner.z, a.corner.z + a.edge);
  return dx * dx + dy * dy + dz * dz;
}

/// Cell coordinate of v along one axis at a level of edge `edge`, clamped to [0, cells - 1].
GLS_INLINE std::int64_t pyramidCoordinate(double v, double origin, double edge, std::int64_t cells)
{
  const double c = (v - origin) / edge;
  if (!(c >= 0.0))
  {
    return 0;
  }
  if (c >= static_cast<double>(cells - 1))
  {
    return cells - 1;
  }
  return static_cast<std::int64_t>(c);
}

/// Index of the top-level cell with Morton key `key` (binary search), or -1.
GLS_INLINE std::int64_t findTopCell(const MultiresolutionView& v, std::uint64_t key)
{
  std::uint64_t lo = 0, hi = v.topEnd - v.topBegin;
  while (lo < hi)
  {
    const std::uint64_t mid = (lo + hi) / 2;
    if (v.topKeys[mid] < key)
    {
      lo = mid + 1;
    }
    else
    {
      hi = mid;
    }
  }
  return lo < v.topEnd - v.topBegin && v.topKeys[lo] == key ? static_cast<std::int64_t>(v.topBegin + lo) : -1;
}

constexpr int kMaxTopCells = 27;
constexpr int kPyramidStack = kMaxTopCells + 8 * (kMaxPyramidLevels + 4);

/// Calls f(index) for each top-level cell that the region grown by r overlaps, z then y then x increasing. The
/// top cells' edge is at least the ball's diameter (or there are two per axis): at most 8 calls for a point, 27
/// for a cube.
template <typename F>
GLS_INLINE void forEachTopCell(const MultiresolutionView& v, const WalkRegion& a, double r, F&& f)
{
  const double H = v.levelSize[v.topLevel];
  const std::int64_t cells = std::int64_t(1) << (kMortonBits - v.topLevel);
  const std::int64_t x0 = pyramidCoordinate(a.corner.x - r, v.origin.x, H, cells);
  const std::int64_t x1 = pyramidCoordinate(a.corner.x + a.edge + r, v.origin.x, H, cells);
  const std::int64_t y0 = pyramidCoordinate(a.corner.y - r, v.origin.y, H, cells);
  const std::int64_t y1 = pyramidCoordinate(a.corner.y + a.edge + r, v.origin.y, H, cells);
  const std::int64_t z0 = pyramidCoordinate(a.corner.z - r, v.origin.z, H, cells);
  const std::int64_t z1 = pyramidCoordinate(a.corner.z + a.edge + r, v.origin.z, H, cells);
  for (std::int64_t z = z0; z <= z1; ++z)
  {
    for (std::int64_t y = y0; y <= y1; ++y)
    {
      for (std::int64_t x = x0; x <= x1; ++x)
      {
        const std::int64_t c = findTopCell(v,
          mortonKey(static_cast<std::uint64_t>(x), static_cast<std::uint64_t>(y), static_cast<std::uint64_t>(z)));
        if (c >= 0)
        {
          f(static_cast<std::uint32_t>(c));
        }
      }
    }
  }
}

} // namespace gls
