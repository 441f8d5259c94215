// A uniform grid over a point set, stored as plain arrays (points sorted by cell, one offset per cell) so that the
// same ball query runs on the host and on the device. Built by NeighborGrid.
#pragma once

#include "gls/Vec3.h"

#include <cstddef>
#include <cstdint>

namespace gls
{

struct GridView
{
  Vec3 origin{};                     ///< lower corner of cell (0, 0, 0)
  double cellSize = 1.0;             ///< edge length of a cubic cell (length unit)
  double invCellSize = 1.0;
  std::int64_t dims[3] = { 1, 1, 1 }; ///< cells along x, y, z
  const std::uint64_t* cellStart = nullptr; ///< points of cell c are [cellStart[c], cellStart[c + 1])
  const Vec3* points = nullptr;      ///< positions sorted by cell
  const Vec3* normals = nullptr;     ///< normals in the same order (may be null)
  const std::uint64_t* ids = nullptr; ///< original index of each sorted point
  std::uint64_t count = 0;           ///< number of points in the grid
};

/// Clamped cell coordinate of a position along one axis.
GLS_INLINE std::int64_t gridCellCoordinate(double v, double origin, double invCell, std::int64_t dim)
{
  const double c = (v - origin) * invCell;
  if (!(c >= 0.0))
  {
    return 0;
  }
  if (c >= static_cast<double>(dim - 1))
  {
    return dim - 1;
  }
  return static_cast<std::int64_t>(c);
}

/// The block of cells [x0, x1] x [y0, y1] x [z0, z1] that a ball of radius r around c overlaps (clamped to the grid).
struct CellBlock
{
  std::int64_t x0, x1, y0, y1, z0, z1;
};

GLS_INLINE CellBlock ballCellBlock(const GridView& g, const Vec3& c, double r)
{
  return { gridCellCoordinate(c.x - r, g.origin.x, g.invCellSize, g.dims[0]),
    gridCellCoordinate(c.x + r, g.origin.x, g.invCellSize, g.dims[0]),
    gridCellCoordinate(c.y - r, g.origin.y, g.invCellSize, g.dims[1]),
    gridCellCoordinate(c.y + r, g.origin.y, g.invCellSize, g.dims[1]),
    gridCellCoordinate(c.z - r, g.origin.z, g.invCellSize, g.dims[2]),
    gridCellCoordinate(c.z + r, g.origin.z, g.invCellSize, g.dims[2]) };
}

/// The sorted points of one grid row (z, y) of the block: [*begin, *end). Cells of one grid row are contiguous in
/// memory, so each row of the cell block is one run of points.
GLS_INLINE void blockRow(
  const GridView& g, const CellBlock& b, std::int64_t z, std::int64_t y, std::uint64_t* begin, std::uint64_t* end)
{
  const std::int64_t row = (z * g.dims[1] + y) * g.dims[0];
  *begin = g.cellStart[row + b.x0];
  *end = g.cellStart[row + b.x1 + 1];
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
      blockRow(g, b, z, y, &begin, &end);
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
