// A uniform grid over a point set, stored as plain arrays (points sorted by cell, one offset per cell) so that the
// same ball query runs on the host and on the device. Built by NeighborGrid.
#pragma once

#include "gls/Numeric.h"
#include "gls/Vec3.h"

#include <cstddef>
#include <cstdint>

namespace gls
{

struct GridView
{
  Vec3 origin{};                     ///< lower corner of lattice cell (0, 0, 0)
  double cellSize = 1.0;             ///< edge length of a cubic cell (length unit)
  double invCellSize = 1.0;
  std::int64_t dims[3] = { 1, 1, 1 }; ///< cells along x, y, z
  /// The lattice coordinates of the grid's first cell: 0 for a grid over its own points; a tile's grid on the whole
  /// cloud's lattice starts where its points do (NeighborGrid::buildOnLattice), so that both sort every point into
  /// the same lattice cell.
  std::int64_t low[3] = { 0, 0, 0 };
  /// The dense cell index: the points of cell c (= (z dims[1] + y) dims[0] + x) are [cellStart[c], cellStart[c + 1]).
  /// Null when the grid keeps the sparse index below instead (gridCellStart reads either).
  const std::uint64_t* cellStart = nullptr;
  /// The sparse cell index, for a grid with many more cells than points (a surface in a k-nearest grid): only the
  /// occupied cells, in cell order. Those of row r (= z dims[1] + y) are entries [rowEntry[r], rowEntry[r + 1]);
  /// entry e is the cell at x = entryX[e] of its row, whose points start at entryStart[e] (entryStart has one entry
  /// more, the point count).
  const std::uint64_t* rowEntry = nullptr;
  const std::int64_t* entryX = nullptr;
  const std::uint64_t* entryStart = nullptr;
  const Vec3* points = nullptr;      ///< positions sorted by cell
  const Vec3* normals = nullptr;     ///< normals in the same order (may be null)
  const std::uint64_t* ids = nullptr; ///< original index of each sorted point
  std::uint64_t count = 0;           ///< number of points in the grid
};

/// Clamped cell coordinate of a position along one axis, in a grid of `dim` cells whose first is lattice cell `low`.
GLS_INLINE std::int64_t gridCellCoordinate(double v, double origin, double invCell, std::int64_t low, std::int64_t dim)
{
  const double c = (v - origin) * invCell;
  if (!(c >= static_cast<double>(low)))
  {
    return 0;
  }
  if (c >= static_cast<double>(low + dim - 1))
  {
    return dim - 1;
  }
  return static_cast<std::int64_t>(c) - low;
}

/// The grid's cell coordinate of a position along axis a (0, 1, 2).
GLS_INLINE std::int64_t gridCellOf(const GridView& g, double v, int a)
{
  const double origin = a == 0 ? g.origin.x : (a == 1 ? g.origin.y : g.origin.z);
  return gridCellCoordinate(v, origin, g.invCellSize, g.low[a], g.dims[a]);
}

/// The lower bound along axis a of the grid's cell `cell` (length unit).
GLS_INLINE double gridCellLowerBound(const GridView& g, int a, std::int64_t cell)
{
  const double origin = a == 0 ? g.origin.x : (a == 1 ? g.origin.y : g.origin.z);
  return origin + static_cast<double>(cell + g.low[a]) * g.cellSize;
}

/// The sparse index's first sorted point of the cell at x of row `row` (= z dims[1] + y): that of the first occupied
/// cell of the row at or after x, or where the next row's points start.
GLS_INLINE std::uint64_t gridSparseCellStart(const GridView& g, std::int64_t row, std::int64_t x)
{
  std::uint64_t lo = g.rowEntry[row], hi = g.rowEntry[row + 1];
  while (lo < hi)
  {
    const std::uint64_t mid = lo + (hi - lo) / 2;
    if (g.entryX[mid] < x)
    {
      lo = mid + 1;
    }
    else
    {
      hi = mid;
    }
  }
  return g.entryStart[lo];
}

/// The first sorted point of the cell at x of row `row` (= z dims[1] + y), 0 <= x <= dims[0]: for an empty cell, and
/// for x = dims[0], where the points of the next occupied cell start. The points of cells x0 to x1 of a row are then
/// [gridCellStart(g, row, x0), gridCellStart(g, row, x1 + 1)), whichever index the grid keeps.
GLS_INLINE std::uint64_t gridCellStart(const GridView& g, std::int64_t row, std::int64_t x)
{
  return g.cellStart != nullptr ? g.cellStart[row * g.dims[0] + x] : gridSparseCellStart(g, row, x);
}

/// The block of cells [x0, x1] x [y0, y1] x [z0, z1] that a ball of radius r around c overlaps (clamped to the
/// grid), with what blockRow needs to narrow each row to the ball.
struct CellBlock
{
  std::int64_t x0, x1, y0, y1, z0, z1;
  Vec3 center;   ///< the ball's center
  double reach;  ///< the ball's radius plus the margin
  double margin; ///< covers the rounding of cell bounds (length unit); negative: rows are not narrowed
};

GLS_INLINE CellBlock ballCellBlock(const GridView& g, const Vec3& c, double r)
{
  CellBlock b;
  b.x0 = gridCellOf(g, c.x - r, 0);
  b.x1 = gridCellOf(g, c.x + r, 0);
  b.y0 = gridCellOf(g, c.y - r, 1);
  b.y1 = gridCellOf(g, c.y + r, 1);
  b.z0 = gridCellOf(g, c.z - r, 2);
  b.z1 = gridCellOf(g, c.z + r, 2);
  b.center = c;
  // A margin far above the rounding of origin + index * cellSize and of the cell assignment of a point.
  const double scale = absolute(c.x) + absolute(c.y) + absolute(c.z) + absolute(g.origin.x) + absolute(g.origin.y) +
    absolute(g.origin.z) +
    g.cellSize * static_cast<double>(g.low[0] + g.low[1] + g.low[2] + g.dims[0] + g.dims[1] + g.dims[2]);
  b.margin = 1e-12 * scale + 1e-9 * r;
  b.reach = r + b.margin;
  if (!isFinite(b.margin) || !isFinite(g.cellSize)) // infinite cells or extents: no narrowing
  {
    b.margin = -1.0;
  }
  return b;
}

/// Distance from v to the interval [lo, hi] (0 inside).
GLS_INLINE double distanceToInterval(double v, double lo, double hi)
{
  return v < lo ? lo - v : (v > hi ? v - hi : 0.0);
}

/// The sorted points of grid row (z, y) of the block that may lie in the ball: [*begin, *end), the row's cells
/// narrowed to the ball's chord through the row's slab (cells of one grid row are contiguous in memory, so this is
/// one run of points). Returns false when the slab misses the ball. Conservative: no point of the ball is left out.
GLS_INLINE bool blockRow(
  const GridView& g, const CellBlock& b, std::int64_t z, std::int64_t y, std::uint64_t* begin, std::uint64_t* end)
{
  std::int64_t x0 = b.x0, x1 = b.x1;
  if (b.margin >= 0.0)
  {
    const double ylo = gridCellLowerBound(g, 1, y);
    const double zlo = gridCellLowerBound(g, 2, z);
    double dy = distanceToInterval(b.center.y, ylo, ylo + g.cellSize) - b.margin;
    double dz = distanceToInterval(b.center.z, zlo, zlo + g.cellSize) - b.margin;
    dy = dy > 0.0 ? dy : 0.0;
    dz = dz > 0.0 ? dz : 0.0;
    const double rest = b.reach * b.reach - dy * dy - dz * dz;
    if (!(rest > 0.0))
    {
      return false;
    }
    const double half = squareRoot(rest) + b.margin;
    const std::int64_t lo = gridCellOf(g, b.center.x - half, 0);
    const std::int64_t hi = gridCellOf(g, b.center.x + half, 0);
    x0 = lo > x0 ? lo : x0;
    x1 = hi < x1 ? hi : x1;
  }
  const std::int64_t row = z * g.dims[1] + y;
  if (g.cellStart != nullptr) // the dense index: the hot path of every ball query
  {
    const std::uint64_t* starts = g.cellStart + row * g.dims[0];
    *begin = starts[x0];
    *end = starts[x1 + 1];
  }
  else
  {
    *begin = gridSparseCellStart(g, row, x0);
    *end = gridSparseCellStart(g, row, x1 + 1);
  }
  return *begin < *end;
}

/// Calls f(sortedIndex, x, d2) for every grid point strictly inside the ball of radius r around c, where
/// x = point - c (local coordinates) and d2 = |x|^2.
template <typename F>
GLS_INLINE void forEachInBall(const GridView& g, const Vec3& c, double r, F&& f)
{
  if (g.count == 0 || !(r > 0.0))
  {
    return;
  }
  const double r2 = r * r;
  const CellBlock b = ballCellBlock(g, c, r);
  for (std::int64_t z = b.z0; z <= b.z1; ++z)
  {
    for (std::int64_t y = b.y0; y <= b.y1; ++y)
    {
      std::uint64_t begin, end;
      if (!blockRow(g, b, z, y, &begin, &end))
      {
        continue;
      }
      for (std::uint64_t i = begin; i < end; ++i)
      {
        const Vec3 x = g.points[i] - c;
        const double d2 = squaredNorm(x);
        if (d2 < r2)
        {
          f(i, x, d2);
        }
      }
    }
  }
}

} // namespace gls
