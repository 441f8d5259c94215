// NeighborGrid owns the arrays behind a GridView: it sorts the admitted points by cell once (a counting sort, stable
// in the original index, so the layout is deterministic) and answers ball and k-nearest queries without any
// O(N^2) step. Points with a non-finite coordinate, or those the caller's mask excludes, are left out.
#pragma once

#include "gls/GridView.h"
#include "gls/KeySort.h"
#include "gls/UninitializedArray.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace gls
{

/// The cells a grid sorts points into: lattice cell (i, j, k) is the cube of edge cellSize whose lower corner is
/// origin + (i, j, k) cellSize, for 0 <= i < dims[0] and so on (coordinates outside are clamped to the lattice).
struct GridLattice
{
  Vec3 origin{};
  double cellSize = 1.0; ///< length unit; infinite for a single cell
  std::int64_t dims[3] = { 1, 1, 1 };
};

class NeighborGrid
{
public:
  /// The lattice build() takes for these points: cells of cellSize from the admitted points' lowest corner, the
  /// cell size enlarged if the grid would need more than max(8 n, 65536) cells.
  static GridLattice chooseLattice(const double* xyz, std::size_t n, double cellSize, const unsigned char* include);

  /// Builds the grid. xyz: n interleaved positions; normals: n interleaved normals or null; include: n flags
  /// (non-zero = admit) or null for all finite points. The cell size is enlarged if the grid would need more than
  /// max(8 n, 65536) cells.
  void build(const double* xyz, const double* normals, std::size_t n, double cellSize,
    const unsigned char* include = nullptr);

  /// Builds a grid over part of a cloud on the whole cloud's lattice (chooseLattice of the whole), covering only the
  /// cells its points occupy: every point falls in the same lattice cell as in the whole cloud's grid, so a ball
  /// query that the part answers completely visits its points in the same order (a spatial tile of a run gives the
  /// same sums as the whole run, bit for bit).
  void buildOnLattice(const double* xyz, const double* normals, std::size_t n, const GridLattice& lattice,
    const unsigned char* include = nullptr);

  const GridView& view() const { return this->View; }
  /// The bytes the grid's arrays hold (their capacity).
  double memoryBytes() const
  {
    return static_cast<double>(this->Points.capacity() + this->Normals.capacity()) * sizeof(Vec3) +
      static_cast<double>(this->Ids.capacity() + this->CellStart.capacity() + this->RowEntry.capacity() +
        this->EntryX.capacity() + this->EntryStart.capacity()) * 8.0;
  }

  /// The threads the next build sorts the points on (1 by default; 0: every hardware thread). The grid is the same
  /// whatever the count.
  void setThreads(int threads) { this->Threads = threads; }

  /// A cell size suited to k-nearest queries on a surface sampled by the admitted points: about sqrt(k) sample
  /// spacings, the spacing estimated from the bounding-box area and the point count.
  static double suggestCellSizeForKNearest(const double* xyz, std::size_t n, int k);

  /// The k nearest grid points to c (fewer if the grid holds fewer), as (squared distance, sorted index), nearest
  /// first, ties broken by the original index. `out` is reused scratch. admitSorted (count flags in the grid's sorted
  /// order, or null): only the points whose flag is non-zero are candidates (the query then visits every cell when
  /// fewer than k are admitted).
  void kNearest(const Vec3& c, int k, std::vector<std::pair<double, std::uint64_t>>& out,
    const unsigned char* admitSorted = nullptr) const;

  /// Scratch of kNearestOfCellRun (one per thread).
  struct CellRunScratch
  {
    std::vector<double> x, y, z, d2;
    std::vector<std::uint64_t> index;
    std::vector<std::size_t> selected;
    std::vector<std::pair<double, std::uint64_t>> out;
    double previousKth = -1.0; ///< the k-th squared distance of the last query answered (negative: none)
  };

  /// The k-nearest queries of the sorted points [first, last), which must lie in one cell (cellRunEnd), answered
  /// together: visit(s, out) receives for each point s the answer of kNearest(points[s], k, out), the same bits. The
  /// points of the cell and of the 26 around it are gathered once and each query takes its k nearest among them; a
  /// query whose k-th is farther than the nearest face of those cells (inside the grid) is asked by kNearest.
  void kNearestOfCellRun(std::uint64_t first, std::uint64_t last, int k, CellRunScratch& scratch,
    const std::function<void(std::uint64_t, const std::vector<std::pair<double, std::uint64_t>>&)>& visit) const;

  /// The end of the sorted points of the cell that sorted point `first` lies in.
  std::uint64_t cellRunEnd(std::uint64_t first) const;

  /// Frees the cells (the largest part of a grid over a surface) and keeps the sorted points and their ids, for a
  /// caller that needs no more queries; view() then has no cellStart and must not be queried.
  void releaseCells();

private:
  void sortIntoCells(const double* xyz, const double* normals, std::size_t n, const unsigned char* include,
    const GridLattice& lattice, const std::int64_t low[3], const std::int64_t dims[3]);

  /// Keeps the sparse cell index (GridView::rowEntry) of the sorted keys instead of the dense one when it is clearly
  /// smaller: a grid of more than about two cells a point. Returns whether it did.
  bool indexOccupiedCells(
    const KeyedIndices& keyed, std::size_t admittedCount, std::size_t cellCount, const std::int64_t dims[3]);

  UninitializedArray<std::uint64_t> CellStart; ///< the dense index (GridView::cellStart), or empty
  UninitializedArray<std::uint64_t> RowEntry;  ///< the sparse index (GridView::rowEntry), or empty
  UninitializedArray<std::int64_t> EntryX;
  UninitializedArray<std::uint64_t> EntryStart;
  UninitializedArray<Vec3> Points;
  UninitializedArray<Vec3> Normals;
  UninitializedArray<std::uint64_t> Ids;
  int Threads = 1;
  GridView View;
};

/// The typical distance between neighbouring points of a surface sampled by `count` points in the box [low, high]:
/// sqrt(area / count), the area spanned by the box's two largest extents (a lower bound of a closed surface's).
double surfaceSpacingOfBox(const double low[3], const double high[3], std::size_t count);

/// The rule of every GLS fit for oriented points: a point enters neighbourhoods when its coordinates are finite and
/// its normal can be normalized (finite, non-zero). Fills unitNormals (3n: the unit normal, NaN where the normal
/// cannot be normalized) and admit (n flags, the `include` mask of NeighborGrid::build).
void normalizeAndAdmit(const double* points, const double* normals, std::size_t n, std::vector<double>& unitNormals,
  std::vector<unsigned char>& admit);

/// normalizeAndAdmit into arrays of 3n and n values that it writes whole, on up to `threads` threads (0: every
/// hardware thread; the same values for any count).
void normalizeAndAdmit(const double* points, const double* normals, std::size_t n, double* unitNormals,
  unsigned char* admit, int threads);

/// The admit flags of normalizeAndAdmit alone (n values, written whole), on up to `threads` threads: for a caller that
/// normalizes the admitted points' normals itself (unitNormal), as the multi-resolution pyramid does while it sorts
/// them.
void admitOrientedPoints(const double* points, const double* normals, std::size_t n, unsigned char* admit, int threads);

/// The unit normal of normalizeAndAdmit: m / |m| into u (3 values) and true, or NaN and false where m cannot be
/// normalized (its length is 0 or not finite).
bool unitNormal(const double* m, double* u);

} // namespace gls
