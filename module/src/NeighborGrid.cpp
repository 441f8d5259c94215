#include "gls/NeighborGrid.h"

#include "gls/Numeric.h"
#include "gls/KeySort.h"
#include "gls/ParallelFor.h"
#include "gls/PointBox.h"

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
  const double len = std::sqrt(roundedSquaredLength(m[0], m[1], m[2])); // as StoredPoints::normal
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
  const PointBox box = boxOfFinitePoints(xyz, n, include);
  const double* lo = box.low;
  const double* hi = box.high;
  const std::size_t admittedCount = box.count;

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

  // Each point's cell as its key (a point left out: the key past the last cell), sorted stably: by cell and, within
  // a cell, by original index, the same layout on any number of threads.
  KeyedIndices keyed(n);
  ParallelOptions options;
  options.threads = this->Threads;
  options.chunk = 65536;
  parallelFor(n, options, [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t i = begin; i < end; ++i)
    {
      std::uint64_t key = cellCount;
      if (admitted(xyz, include, i))
      {
        const double* p = xyz + 3 * i;
        key = static_cast<std::uint64_t>(
          (gridCellOf(v, p[2], 2) * dims[1] + gridCellOf(v, p[1], 1)) * dims[0] + gridCellOf(v, p[0], 0));
      }
      keyed[i] = { key, i };
    }
  });
  sortByKey(keyed, this->Threads);
  const std::size_t admittedCount = static_cast<std::size_t>(
    std::lower_bound(keyed.begin(), keyed.end(), cellCount,
      [](const KeyedIndex& k, std::uint64_t c) { return k.key < c; }) -
    keyed.begin());
  this->Points.resize(admittedCount);
  this->Ids.resize(admittedCount);
  this->Normals.resize(normals ? admittedCount : 0);
  const bool sparse = this->indexOccupiedCells(keyed, admittedCount, cellCount, dims);
  if (!sparse)
  {
    this->CellStart.resize(cellCount + 1);
  }
  // Each slot's point, and (dense index) the starts of the cells from the one after the previous slot's up to its
  // own (each start written once, by the first slot at or after it).
  parallelFor(admittedCount, options, [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t slot = begin; slot < end; ++slot)
    {
      const std::uint64_t i = keyed[slot].index;
      this->Points[slot] = { xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] };
      this->Ids[slot] = i;
      if (normals)
      {
        this->Normals[slot] = { normals[3 * i], normals[3 * i + 1], normals[3 * i + 2] };
      }
      const std::uint64_t from = slot == 0 ? 0 : keyed[slot - 1].key + 1;
      for (std::uint64_t c = from; !sparse && c <= keyed[slot].key; ++c)
      {
        this->CellStart[c] = slot;
      }
    }
  });
  if (!sparse)
  {
    const std::uint64_t after = admittedCount == 0 ? 0 : keyed[admittedCount - 1].key + 1;
    parallelFor(cellCount + 1 - after, options, [&](std::size_t begin, std::size_t end, int) {
      std::fill(this->CellStart.begin() + static_cast<std::ptrdiff_t>(after + begin),
        this->CellStart.begin() + static_cast<std::ptrdiff_t>(after + end), admittedCount);
    });
  }
  v.cellStart = sparse ? nullptr : this->CellStart.data();
  v.rowEntry = sparse ? this->RowEntry.data() : nullptr;
  v.entryX = sparse ? this->EntryX.data() : nullptr;
  v.entryStart = sparse ? this->EntryStart.data() : nullptr;
  v.points = this->Points.data();
  v.normals = normals ? this->Normals.data() : nullptr;
  v.ids = this->Ids.data();
  v.count = admittedCount;
}

bool NeighborGrid::indexOccupiedCells(
  const KeyedIndices& keyed, std::size_t admittedCount, std::size_t cellCount, const std::int64_t dims[3])
{
  this->RowEntry.clear();
  this->EntryX.clear();
  this->EntryStart.clear();
  // A dense index of at most about two entries a point is kept: it is the fastest to read.
  if (static_cast<double>(cellCount) <= 2.0 * static_cast<double>(admittedCount) + 65536.0)
  {
    return false;
  }
  std::size_t occupied = 0;
  for (std::size_t slot = 0; slot < admittedCount; ++slot)
  {
    occupied += slot == 0 || keyed[slot].key != keyed[slot - 1].key ? 1 : 0;
  }
  const std::size_t rows = static_cast<std::size_t>(dims[1] * dims[2]);
  // The sparse index only where it is clearly smaller (a cloud of few points per row of cells keeps the dense one).
  const double sparseBytes = 8.0 * static_cast<double>(rows) + 16.0 * static_cast<double>(occupied);
  if (2.0 * sparseBytes > 8.0 * static_cast<double>(cellCount))
  {
    return false;
  }
  this->RowEntry.resize(rows + 1);
  this->EntryX.resize(occupied);
  this->EntryStart.resize(occupied + 1);
  const std::uint64_t width = static_cast<std::uint64_t>(dims[0]);
  std::size_t e = 0, nextRow = 0;
  for (std::size_t slot = 0; slot < admittedCount; ++slot)
  {
    const std::uint64_t key = keyed[slot].key;
    if (slot > 0 && key == keyed[slot - 1].key)
    {
      continue;
    }
    for (const std::size_t row = static_cast<std::size_t>(key / width); nextRow <= row; ++nextRow)
    {
      this->RowEntry[nextRow] = e; // rows up to this cell's start at it
    }
    this->EntryX[e] = static_cast<std::int64_t>(key % width);
    this->EntryStart[e] = slot;
    ++e;
  }
  for (; nextRow <= rows; ++nextRow)
  {
    this->RowEntry[nextRow] = e;
  }
  this->EntryStart[e] = admittedCount;
  return true;
}

double NeighborGrid::suggestCellSizeForKNearest(const double* xyz, std::size_t n, int k)
{
  const PointBox box = boxOfFinitePoints(xyz, n);
  const double size =
    surfaceSpacingOfBox(box.low, box.high, box.count) * std::sqrt(static_cast<double>(std::max(k, 1)));
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

void NeighborGrid::releaseCells()
{
  UninitializedArray<std::uint64_t>().swap(this->CellStart);
  UninitializedArray<std::uint64_t>().swap(this->RowEntry);
  UninitializedArray<std::int64_t>().swap(this->EntryX);
  UninitializedArray<std::uint64_t>().swap(this->EntryStart);
  this->View.cellStart = nullptr;
  this->View.rowEntry = nullptr;
  this->View.entryX = nullptr;
  this->View.entryStart = nullptr;
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
