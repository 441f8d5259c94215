// The multi-resolution evaluation's rule of which cells are one sample (docs/math.md, "Multi-resolution
// evaluation"), host/device: a cell is taken whole where it is small against its distance from the evaluation point
// (edge <= Accuracy * distance to the cell's box, and within the smallest scale a share of it), else its points are
// read one by one; and the reading of a node's points and sums.
#pragma once

#include "gls/MultiresolutionView.h"

namespace gls
{

/// Within the smallest scale, cells are held to this share of epsilon (times the smallest scale): they enter every
/// ball, the smallest ones among few other samples. The lattice is scaled so that the near cells are 0.8 to 1 times
/// this limit (nearCellEdge in MultiresolutionCloud.h). Measured (docs/performance.md, "The lattice scaled with the
/// smallest scale"; epsilon 0.5, 1M points, rocker arm / bunny): near cells of 0.314 / 0.305 of the smallest scale
/// give nu p99 0.087 / 0.079 and a 10M core (with its build) 1.29x / 1.13x faster than the 0.21 / 0.24 of the
/// earlier power-of-two lattice with a share of 0.8 (nu p99 0.074 / 0.066); on the rocker arm, near cells of 0.28 and
/// 0.36 of it (a scratch build scaling the lattice freely) gave nu p99 0.076 and 0.091.
constexpr double kNearAccuracyShare = 0.64;

/// The squared edge a cell nearer than the smallest scale may have (takenWhole): (kNearAccuracyShare epsilon times the
/// smallest scale)^2, from eps2 = epsilon^2 and floor2 = the smallest scale squared. The pyramid's levels are scaled
/// from it (nearCellEdge in MultiresolutionCloud.h), with this arithmetic, so that one level meets it exactly.
GLS_INLINE double squaredNearCellLimit(double eps2, double floor2)
{
  constexpr double nearShare2 = kNearAccuracyShare * kNearAccuracyShare;
  return eps2 * (nearShare2 * floor2);
}

/// The rule of both walks: a cell of squared edge edge2, at squared distance box2 from p's region, is taken whole
/// when its edge is at most epsilon times its distance, or, nearer than the smallest scale, kNearAccuracyShare
/// epsilon times the smallest scale (eps2 = epsilon^2, floor2 = the smallest scale squared: such a cell contributes
/// to no smaller ball, so its edge against every scale stays below epsilon), and p is at least one edge away from it
/// (p's nearest neighbours enter point by point).
GLS_INLINE bool takenWhole(double edge2, double box2, double eps2, double floor2)
{
  return edge2 <= box2 && edge2 <= (box2 > floor2 ? eps2 * box2 : squaredNearCellLimit(eps2, floor2));
}

/// The points [first, last) of the cell `node` of level `level` (a cell's points are contiguous).
GLS_INLINE void pointRange(const PyramidNode* nodes, std::uint32_t node, int level, std::uint32_t& first,
  std::uint32_t& last)
{
  std::uint32_t a = node, z = node;
  for (int l = level; l > 0; --l)
  {
    a = nodes[a].first;
    z = nodes[z].last - 1;
  }
  first = nodes[a].first;
  last = nodes[z].last;
}

/// A cell taken whole (takenWhole) below the pyramid's summed levels (whose sums a walk forms from its points) that
/// holds fewer points than this is read point by point instead: its points enter exactly, and one to three points
/// cost less to bin one by one than a cell's sample, whose spread meets 2.1 shells on average, each adding the
/// cell's F and H (docs/performance.md, "The CPU kernel": a quarter of the cells taken whole at 1M points held three
/// points or fewer, four fifths of them below the summed levels).
constexpr std::uint32_t kFewestPointsOfACellSample = 4;

/// Where the walks (forEachMultiresolutionSample, and the CPU kernel's level by level) find the points [first,
/// last) of a cell taken whole: true when it is below the summed levels and holds too few points for a cell sample
/// (kFewestPointsOfACellSample). The summed levels are left as they are: finding a cell's points there descends the
/// pyramid, which cost more than it saved at 10M points.
GLS_INLINE bool readPointByPoint(const MultiresolutionView& v, std::uint32_t node, int level, std::uint32_t& first,
  std::uint32_t& last)
{
  if (level >= v.summedLevel)
  {
    return false;
  }
  pointRange(v.nodes, node, level, first, last);
  return last - first < kFewestPointsOfACellSample;
}

/// The sums a cell of the moment set Set keeps formed from the points of the cell `node` of level `level` (below the
/// summed levels), about its corner, as the build forms those of level summedLevel.
template <typename Set>
GLS_FORCE_INLINE void formCellOfNode(
  const MultiresolutionView& v, std::uint32_t node, int level, typename Set::Cell& cell)
{
  std::uint32_t first = 0, last = 0;
  pointRange(v.nodes, node, level, first, last);
  formCellOfPoints<Set>(v.points, first, last, nodeCorner(v.origin, v.nodes[node], v.levelSize[level]), cell);
}

/// The sums of the cell `node` of level `level` that the moment set Set keeps: stored (`cells`, those of levels
/// summedLevel and above, node i's at cells[i - summedBegin]), or formed from its points (formCellOfNode).
template <typename Set>
GLS_INLINE void cellMoments(const MultiresolutionView& v, const typename Set::Cell* cells, std::uint32_t node,
  int level, typename Set::Cell& cell)
{
  if (level >= v.summedLevel)
  {
    cell = cells[node - v.summedBegin];
    return;
  }
  formCellOfNode<Set>(v, node, level, cell);
}

/// cellMoments inlined into its caller, a stored cell read where it is: the stored sums, or `formed` formed.
template <typename Set>
GLS_FORCE_INLINE const typename Set::Cell& cellMomentsOf(const MultiresolutionView& v, const typename Set::Cell* cells,
  std::uint32_t node, int level, typename Set::Cell& formed)
{
  if (level >= v.summedLevel)
  {
    return cells[node - v.summedBegin];
  }
  formCellOfNode<Set>(v, node, level, formed);
  return formed;
}

/// The oriented sphere's cell sums: the pyramid's own (v.cells).
GLS_INLINE void cellMoments(const MultiresolutionView& v, std::uint32_t node, int level, PyramidCell& cell)
{
  cellMoments<OrientedSphereMoments>(v, v.cells, node, level, cell);
}

} // namespace gls
