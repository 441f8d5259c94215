#include "gls/NeighborGrid.h"

#include "gls/Numeric.h"
#include "gls/ParallelFor.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gls
{
namespace
{

bool finitePoint(const double* p)
{
  return isFinite(p[0]) && isFinite(p[1]) && isFinite(p[2]);
}

/// |m| where m can be normalized (its length is finite and positive), else 0.
double normalizableLength(const double* m)
{
  const double len = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
  return len > 0.0 && isFinite(len) ? len : 0.0;
}

bool admitted(const double* xyz, const unsigned char* include, std::size_t i)
{
  return (include == nullptr || include[i] != 0) && finitePoint(xyz + 3 * i);
}

} // namespace

GridLattice NeighborGrid::chooseLattice(
  const double* xyz, std::size_t n, double cellSize, const unsigned char* include)
{
  double lo[3] = { 0, 0, 0 }, hi[3] = { 0, 0, 0 };
  std::size_t admittedCount = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (!admitted(xyz, include, i))
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      const double v = xyz[3 * i + a];
      lo[a] = admittedCount == 0 ? v : std::min(lo[a], v);
      hi[a] = admittedCount == 0 ? v : std::max(hi[a], v);
    }
    ++admittedCount;
  }

  double extent = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    extent = std::max(extent, hi[a] - lo[a]);
  }
  if (!(cellSize > 0.0) || !isFinite(cellSize))
  {
    cellSize = extent > 0.0 ? extent : 1.0;
  }
  // Keep the cell array proportional to the point count. Extents that overflow (finite points 1e308 apart) or a
  // cell size that cannot be fitted get a single cell: slow on such data, but never wrong and never a hang.
  const double maxCells = std::max(8.0 * static_cast<double>(admittedCount), 65536.0);
  GridLattice lattice;
  bool fitted = false;
  for (int attempt = 0; attempt < 256 && isFinite(cellSize) && cellSize > 0.0; ++attempt)
  {
    double cells = 1.0;
    for (int a = 0; a < 3; ++a)
    {
      const double d = std::floor((hi[a] - lo[a]) / cellSize) + 1.0;
      cells *= d;
      lattice.dims[a] = isFinite(d) ? static_cast<std::int64_t>(std::min(d, 4.0e9)) : 1;
    }
    if (isFinite(cells) && cells <= maxCells)
    {
      fitted = true;
      break;
    }
    cellSize *= std::max(1.01, std::cbrt(isFinite(cells) ? cells / maxCells : 2.0));
  }
  if (!fitted)
  {
    lattice.dims[0] = lattice.dims[1] = lattice.dims[2] = 1;
    cellSize = std::numeric_limits<double>::infinity();
  }
  lattice.origin = { lo[0], lo[1], lo[2] };
  lattice.cellSize = cellSize;
  return lattice;
}

void NeighborGrid::build(
  const double* xyz, const double* normals, std::size_t n, double cellSize, const unsigned char* include)
{
  const GridLattice lattice = chooseLattice(xyz, n, cellSize, include);
  const std::int64_t low[3] = { 0, 0, 0 };
  this->sortIntoCells(xyz, normals, n, include, lattice, low, lattice.dims);
}

void NeighborGrid::buildOnLattice(
  const double* xyz, const double* normals, std::size_t n, const GridLattice& lattice, const unsigned char* include)
{
  // The lattice cells of the admitted points (clamped to the lattice, as the whole cloud's grid clamps them).
  const double inv = isFinite(lattice.cellSize) ? 1.0 / lattice.cellSize : 0.0;
  const double origin[3] = { lattice.origin.x, lattice.origin.y, lattice.origin.z };
  std::int64_t low[3] = { 0, 0, 0 }, high[3] = { 0, 0, 0 };
  bool any = false;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (!admitted(xyz, include, i))
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      const std::int64_t c = gridCellCoordinate(xyz[3 * i + a], origin[a], inv, 0, lattice.dims[a]);
      low[a] = any ? std::min(low[a], c) : c;
      high[a] = any ? std::max(high[a], c) : c;
    }
    any = true;
  }
  const std::int64_t dims[3] = { high[0] - low[0] + 1, high[1] - low[1] + 1, high[2] - low[2] + 1 };
  this->sortIntoCells(xyz, normals, n, include, lattice, low, dims);
}

void NeighborGrid::sortIntoCells(const double* xyz, const double* normals, std::size_t n,
  const unsigned char* include, const GridLattice& lattice, const std::int64_t low[3], const std::int64_t dims[3])
{
  GridView& v = this->View;
  v.origin = lattice.origin;
  v.cellSize = lattice.cellSize;
  v.invCellSize = isFinite(lattice.cellSize) ? 1.0 / lattice.cellSize : 0.0;
  for (int a = 0; a < 3; ++a)
  {
    v.dims[a] = dims[a];
    v.low[a] = low[a];
  }
  const std::size_t cellCount = static_cast<std::size_t>(dims[0] * dims[1] * dims[2]);

  // Counting sort by cell, stable in the original index.
  std::vector<std::uint64_t> cellOf(n, 0);
  this->CellStart.assign(cellCount + 1, 0);
  std::size_t admittedCount = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (!admitted(xyz, include, i))
    {
      continue;
    }
    const double* p = xyz + 3 * i;
    const std::int64_t cx = gridCellOf(v, p[0], 0);
    const std::int64_t cy = gridCellOf(v, p[1], 1);
    const std::int64_t cz = gridCellOf(v, p[2], 2);
    cellOf[i] = static_cast<std::uint64_t>((cz * dims[1] + cy) * dims[0] + cx);
    ++this->CellStart[cellOf[i] + 1];
    ++admittedCount;
  }
  for (std::size_t c = 0; c < cellCount; ++c)
  {
    this->CellStart[c + 1] += this->CellStart[c];
  }
  this->Points.resize(admittedCount);
  this->Ids.resize(admittedCount);
  this->Normals.resize(normals ? admittedCount : 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    if (!admitted(xyz, include, i))
    {
      continue;
    }
    const std::uint64_t slot = this->CellStart[cellOf[i]]++; // the cell's next slot
    this->Points[slot] = { xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] };
    this->Ids[slot] = i;
    if (normals)
    {
      this->Normals[slot] = { normals[3 * i], normals[3 * i + 1], normals[3 * i + 2] };
    }
  }
  restoreBucketStarts(this->CellStart);
  v.cellStart = this->CellStart.data();
  v.points = this->Points.data();
  v.normals = normals ? this->Normals.data() : nullptr;
  v.ids = this->Ids.data();
  v.count = admittedCount;
}

double NeighborGrid::suggestCellSizeForKNearest(const double* xyz, std::size_t n, int k)
{
  double lo[3] = { 0, 0, 0 }, hi[3] = { 0, 0, 0 };
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (!finitePoint(xyz + 3 * i))
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      const double v = xyz[3 * i + a];
      lo[a] = count == 0 ? v : std::min(lo[a], v);
      hi[a] = count == 0 ? v : std::max(hi[a], v);
    }
    ++count;
  }
  const double size = surfaceSpacingOfBox(lo, hi, count) * std::sqrt(static_cast<double>(std::max(k, 1)));
  return size > 0.0 ? size : 1.0;
}

double surfaceSpacingOfBox(const double low[3], const double high[3], std::size_t count)
{
  double e[3] = { high[0] - low[0], high[1] - low[1], high[2] - low[2] };
  std::sort(e, e + 3);
  // A surface sample: the two largest extents span the area that holds the points.
  const double area = std::max(e[2] * e[1], e[2] * e[2] * 1e-6);
  return std::sqrt(area / static_cast<double>(std::max<std::size_t>(count, 1)));
}

void NeighborGrid::kNearest(const Vec3& c, int k, std::vector<std::pair<double, std::uint64_t>>& out,
  const unsigned char* admitSorted) const
{
  out.clear();
  const GridView& g = this->View;
  if (k <= 0 || g.count == 0)
  {
    return;
  }
  const std::size_t want = std::min<std::size_t>(static_cast<std::size_t>(k), g.count);
  out.reserve(want);
  // `out` is kept sorted by (squared distance, original index), nearest first: a candidate enters by insertion
  // (the few that beat the current k-th), most are rejected by one comparison with the k-th's distance.
  const auto closerThan = [&g](double d2, std::uint64_t i, const std::pair<double, std::uint64_t>& o) {
    return d2 < o.first || (d2 == o.first && g.ids[i] < g.ids[o.second]);
  };
  const auto offer = [&](double d2, std::uint64_t i) {
    if (out.size() == want)
    {
      if (d2 > out.back().first || !closerThan(d2, i, out.back()))
      {
        return;
      }
      out.pop_back();
    }
    std::size_t j = out.size();
    out.emplace_back(d2, i);
    for (; j > 0 && closerThan(d2, i, out[j - 1]); --j)
    {
      out[j] = out[j - 1];
    }
    out[j] = { d2, i };
  };
  // The squared distance below which no unvisited point can beat the k-th kept one (infinity until k are kept).
  const auto worst = [&]() {
    return out.size() == want ? out.back().first : std::numeric_limits<double>::infinity();
  };

  const std::int64_t cc[3] = { gridCellOf(g, c.x, 0), gridCellOf(g, c.y, 1), gridCellOf(g, c.z, 2) };
  const std::int64_t maxRing = std::max({ g.dims[0], g.dims[1], g.dims[2] });
  // Cells and rows farther from c than the k-th kept point are skipped. Their distance is computed from the cell
  // bounds origin + index * cellSize, less a margin far above the rounding of those bounds and of the cells the
  // points were sorted into (that of ballCellBlock), so no point that could enter is skipped.
  const CellBlock bounds = ballCellBlock(g, c, 0.0);
  const bool prune = bounds.margin >= 0.0;
  const auto axisGap = [&](double v, int axis, std::int64_t cell) {
    const double lo = gridCellLowerBound(g, axis, cell);
    const double d = distanceToInterval(v, lo, lo + g.cellSize) - bounds.margin;
    return d > 0.0 ? d * d : 0.0;
  };
  const auto visitRun = [&](std::int64_t row, std::int64_t xa, std::int64_t xb) {
    for (std::uint64_t i = g.cellStart[row + xa]; i < g.cellStart[row + xb + 1]; ++i)
    {
      if (admitSorted == nullptr || admitSorted[i] != 0)
      {
        offer(squaredNorm(g.points[i] - c), i);
      }
    }
  };

  for (std::int64_t ring = 0; ring <= maxRing; ++ring)
  {
    const std::int64_t z0 = std::max<std::int64_t>(cc[2] - ring, 0), z1 = std::min(cc[2] + ring, g.dims[2] - 1);
    const std::int64_t y0 = std::max<std::int64_t>(cc[1] - ring, 0), y1 = std::min(cc[1] + ring, g.dims[1] - 1);
    const std::int64_t xl = cc[0] - ring, xh = cc[0] + ring;
    const std::int64_t x0 = std::max<std::int64_t>(xl, 0), x1 = std::min(xh, g.dims[0] - 1);
    // The ring's cells: whole rows where the row is on the ring's shell (z or y at the ring's distance), only the
    // two end cells of the rows inside it (none where both ends are off the grid: a thin grid costs O(1) a ring).
    const bool ends = xl >= 0 || xh < g.dims[0];
    const auto visitRow = [&](std::int64_t z, std::int64_t y, double gz, bool shell) {
      const double gyz = prune ? gz + axisGap(c.y, 1, y) : 0.0;
      if (gyz > worst())
      {
        return; // the whole row is farther than the k-th kept point
      }
      const std::int64_t row = (z * g.dims[1] + y) * g.dims[0];
      if (shell)
      {
        // One run of the row's cells, less those at its ends that are too far.
        std::int64_t a = x0, b = x1;
        while (prune && a <= b && gyz + axisGap(c.x, 0, a) > worst())
        {
          ++a;
        }
        while (prune && b >= a && gyz + axisGap(c.x, 0, b) > worst())
        {
          --b;
        }
        if (a <= b)
        {
          visitRun(row, a, b);
        }
        return;
      }
      for (const std::int64_t x : { xl, xh })
      {
        if (x >= 0 && x < g.dims[0] && (x == xl || xh != xl) &&
          (!prune || gyz + axisGap(c.x, 0, x) <= worst()))
        {
          visitRun(row, x, x);
        }
      }
    };
    const auto visitLayer = [&](std::int64_t z) {
      const double gz = prune ? axisGap(c.z, 2, z) : 0.0;
      if (std::abs(z - cc[2]) == ring)
      {
        for (std::int64_t y = y0; y <= y1; ++y)
        {
          visitRow(z, y, gz, true);
        }
        return;
      }
      for (const std::int64_t y : { cc[1] - ring, cc[1] + ring })
      {
        if (y >= 0 && y < g.dims[1])
        {
          visitRow(z, y, gz, true);
        }
      }
      for (std::int64_t y = std::max(y0, cc[1] - ring + 1); ends && y <= std::min(y1, cc[1] + ring - 1); ++y)
      {
        visitRow(z, y, gz, false);
      }
    };
    // The layers inside the ring's z range hold ring cells only on the y shell or at the x ends: where neither is
    // on the grid, only the two shell layers are walked.
    if (ring == 0 || cc[1] - ring >= 0 || cc[1] + ring < g.dims[1] || ends)
    {
      for (std::int64_t z = z0; z <= z1; ++z)
      {
        visitLayer(z);
      }
    }
    else
    {
      for (const std::int64_t z : { cc[2] - ring, cc[2] + ring })
      {
        if (z >= 0 && z < g.dims[2])
        {
          visitLayer(z);
        }
      }
    }
    // Every point outside this ring's block of cells is at least `ring` cells away from c's cell; once the block
    // covers the grid, every point was offered (what ends a masked query that admits fewer than k).
    const double reach = static_cast<double>(ring) * g.cellSize;
    const bool covered = ring >= std::max({ cc[0], g.dims[0] - 1 - cc[0], cc[1], g.dims[1] - 1 - cc[1], cc[2],
                                   g.dims[2] - 1 - cc[2] });
    if ((out.size() == want && out.back().first <= reach * reach) || covered)
    {
      break;
    }
  }
}

void NeighborGrid::releaseCells()
{
  std::vector<std::uint64_t>().swap(this->CellStart);
  this->View.cellStart = nullptr;
}

void normalizeAndAdmit(const double* points, const double* normals, std::size_t n, std::vector<double>& unitNormals,
  std::vector<unsigned char>& admit)
{
  unitNormals.resize(3 * n);
  admit.resize(n);
  normalizeAndAdmit(points, normals, n, unitNormals.data(), admit.data(), 1);
}

void normalizeAndAdmit(const double* points, const double* normals, std::size_t n, double* unitNormals,
  unsigned char* admit, int threads)
{
  ParallelOptions options;
  options.threads = threads;
  options.chunk = 65536;
  parallelFor(n, options, [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t i = begin; i < end; ++i)
    {
      const bool normalizable = unitNormal(normals + 3 * i, unitNormals + 3 * i);
      admit[i] = normalizable && finitePoint(points + 3 * i) ? 1 : 0;
    }
  });
}

void admitOrientedPoints(const double* points, const double* normals, std::size_t n, unsigned char* admit, int threads)
{
  ParallelOptions options;
  options.threads = threads;
  options.chunk = 65536;
  parallelFor(n, options, [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t i = begin; i < end; ++i)
    {
      admit[i] = normalizableLength(normals + 3 * i) > 0.0 && finitePoint(points + 3 * i) ? 1 : 0;
    }
  });
}

bool unitNormal(const double* m, double* u)
{
  const double len = normalizableLength(m);
  for (int a = 0; a < 3; ++a)
  {
    u[a] = len > 0.0 ? m[a] / len : std::numeric_limits<double>::quiet_NaN();
  }
  return len > 0.0;
}

} // namespace gls
