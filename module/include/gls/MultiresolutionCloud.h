// MultiresolutionCloud owns the arrays behind a MultiresolutionView: the admitted points sorted by their Morton key
// on a lattice of cubes of edge h0 (ties by original index, so the layout is deterministic), the cells of level 0
// (runs of equal keys) and of every coarser level up to cells at least as large as the ball of the largest scale,
// each with the exact sums of its points. Memory is O(N): the sorted points and at most as many cells as points.
// The levels are built on all threads, each cell by one thread, so the result does not depend on the thread count.
#pragma once

#include "gls/MultiresolutionView.h"
#include "gls/ParallelFor.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gls
{

/// The finest level whose cells keep their sums (PyramidCell); the cells of finer levels, of about 1.5 and 3 points
/// each on a surface, form theirs from their points when a walk takes them whole.
constexpr int kFirstSummedLevel = 2;

/// How a pyramid is laid out. Two pyramids built with the same layout over clouds that agree within the reach of
/// an evaluation point give that point the same samples (this is what makes distributed runs equal serial ones).
struct PyramidLayout
{
  double finestCellSize = 0.0; ///< h0 (length unit); must be > 0
  double largestScale = 0.0;   ///< the top level's cells are at least twice this (or the 2^21 lattice is full)
  Vec3 low{};                  ///< a corner below every point; the lattice origin is snapped below it
  double accuracy = 0.1;       ///< a cell is one sample where edge <= accuracy * distance
  int walkLevel = 0;           ///< the points of one cube of this level share a walk (MultiresolutionView)
  double linearizedDistance = kLinearizedDistance; ///< where the far parts begin (MultiresolutionView, FarRule)
};

/// The layout for a cloud whose admitted points lie in [low, high]: h0 the power of two at or below twice `spacing`
/// (the typical distance between neighbouring points), enlarged until the lattice of 2^21 cells per axis covers the
/// box; walks shared by cubes of up to 4 h0 no larger than the smallest scale.
PyramidLayout choosePyramidLayout(const double low[3], const double high[3], double spacing, double smallestScale,
  double largestScale, double accuracy);

class MultiresolutionCloud
{
public:
  /// Builds the pyramid of the points with admit[i] != 0 (finite coordinates and unit normals required).
  /// parallel.progress receives the fraction done; returns false if it asked to abort (the cloud is then empty).
  bool build(const double* xyz, const double* unitNormals, std::size_t n, const unsigned char* admit,
    const PyramidLayout& layout, const ParallelOptions& parallel);

  const MultiresolutionView& view() const { return this->View; }
  /// Original indices of the points in pyramid order (a locality-preserving evaluation order).
  const std::vector<std::uint64_t>& ids() const { return this->Ids; }
  /// Nodes of every level (PyramidNode), and the cells with stored sums (levels kFirstSummedLevel and above).
  std::size_t nodeCount() const { return this->Nodes.size(); }
  std::size_t cellCount() const { return this->Cells.size(); }
  /// Bytes held (points, normals, ids, cells).
  double bytes() const;

private:
  std::vector<Vec3> Points;
  std::vector<Vec3> Normals;
  std::vector<std::uint64_t> Ids;
  std::vector<PyramidNode> Nodes;
  std::vector<PyramidCell> Cells;
  std::vector<std::uint64_t> TopKeys;
  std::size_t SummedBegin = 0;
  MultiresolutionView View;
};

} // namespace gls
