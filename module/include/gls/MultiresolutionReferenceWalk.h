// The multi-resolution evaluation of one point, host/device: the reference walk down the pyramid
// (forEachMultiresolutionSample: every cell taken whole and every point read one by one, for one ball) and the
// evaluation of every scale from its samples (evaluateAllScalesMultiresolution; by windows of scales on the CUDA
// device). The CPU engine's kernel (MultiresolutionKernel.h) is tested against it; the moments and fits are the exact
// pass's (AggregateMoments.h, fitAllScalesFromBins).
#pragma once

#include "gls/AggregateMoments.h"
#include "gls/MultiresolutionFarRule.h"
#include "gls/MultiresolutionTakeWhole.h"
#include "gls/PointScaleSpace.h"

namespace gls
{

/// Calls sample(node, level, farPart) for every cell taken whole (takenWhole, with `smallest` the smallest scale;
/// not readPointByPoint) and point(i) for every point read one by one, for the ball of radius r around p: every point
/// of the ball is in exactly one of them (points of a cell taken whole may lie outside the ball; the caller bins them
/// by its CellSample's spread). Distances are measured from p's walkRegion, or, for the cells of a far part
/// (FarRule, placeCell), from its far region, so the samples and their order are fixed by the pyramid and those
/// regions alone; farPart is i + 1 for a linearized cell of far part i, else 0.
template <typename CellVisit, typename PointVisit>
GLS_INLINE void forEachMultiresolutionSample(const MultiresolutionView& v, const Vec3& p, double r, double smallest,
  CellVisit&& sample, PointVisit&& point)
{
  const double floor2 = smallest * smallest;
  if (v.topEnd <= v.topBegin || !(r > 0.0))
  {
    return;
  }
  const double r2 = r * r;
  const double eps2 = v.accuracy * v.accuracy;
  std::uint32_t stack[kPyramidStack];
  int stackLevel[kPyramidStack];
  int top = 0;
  // The top-level cells the balls of p's far region overlap (it holds p's walk region), pushed last to first so that
  // they are visited in order.
  const WalkRegion region = walkRegion(v, p);
  const FarRule far = farRule(v, p);
  std::uint32_t tops[kMaxTopCells];
  int found = 0;
  forEachTopCell(v, outermostRegion(far, region), r, [&](std::uint32_t c) {
    if (found < kMaxTopCells)
    {
      tops[found++] = c;
    }
  });
  for (int i = found - 1; i >= 0; --i)
  {
    stack[top] = tops[i];
    stackLevel[top] = v.topLevel;
    ++top;
  }
  while (top > 0)
  {
    --top;
    const PyramidNode& cell = v.nodes[stack[top]];
    const int level = stackLevel[top];
    const double edge = v.levelSize[level];
    const CellPlace place = placeCell(far, region, nodeCorner(v.origin, cell, edge), edge);
    if (!(place.box2 < r2))
    {
      continue;
    }
    // A cell taken whole enters as its sample, or point by point where it holds too few points (not in the far
    // part); a level-0 cell not taken whole is read point by point.
    const bool whole = takenWhole(edge * edge, place.box2, eps2, floor2);
    std::uint32_t first = cell.first, last = cell.last;
    if (whole && (place.far > 0 || !readPointByPoint(v, stack[top], level, first, last)))
    {
      sample(stack[top], level, place.linearized);
    }
    else if (whole || level == 0)
    {
      for (std::uint32_t i = first; i < last; ++i)
      {
        point(i);
      }
    }
    else
    {
      // Children pushed last to first, so that they are visited in pyramid order.
      for (std::uint32_t c = cell.last; c > cell.first && top < kPyramidStack; --c)
      {
        stack[top] = c - 1;
        stackLevel[top] = level - 1;
        ++top;
      }
    }
  }
}

/// The terms of the ball of the largest scale around p, each with its bin k: cellShare(k, sample, share) for each
/// shell a cell taken whole meets (its CellSample: its points weighted by a linear field, their squared distances
/// spread over the shells; a linearized cell's shares formed at its far region's centre and moved to p, movedShare),
/// point(k, x, d2, normal) for each point read one by one inside the ball (x = its position - p, d2 = |x|^2). The
/// walk (forEachMultiresolutionSample) fixes the terms and their order. Set: the moment set (MomentSet.h), whose cell
/// sums of the levels summedLevel and above are `cells` (cellMoments).
template <typename Set, typename CellShare, typename PointTerm>
GLS_INLINE void forEachMultiresolutionTerm(const MultiresolutionView& v, const typename Set::Cell* cells,
  const Vec3& p, const ScaleBinning& b, CellShare&& cellShare, PointTerm&& point)
{
  const double r = b.scales[b.count - 1];
  const double r2 = r * r;
  const Vec3 anchor = regionCentre(walkRegion(v, p));
  const FarRule far = farRule(v, p);
  forEachMultiresolutionSample(
    v, p, r, b.scales[0],
    [&](std::uint32_t node, int level, int farPart) {
      typename Set::Cell cell;
      cellMoments<Set>(v, cells, node, level, cell);
      CellSampleT<Set> s;
      // A far cell too narrow to linearize is sampled as a near cell (direction from the walk region's centre).
      const Vec3 centre = farPart > 0 ? regionCentre(far.region[farPart - 1]) : anchor;
      const bool linearized = farPart > 0 &&
        linearizable(spreadHalfWidth(cell, cell.centroid - centre), cell.centroid - centre, far.region[farPart - 1]);
      const Vec3 a = cell.centroid - (linearized ? centre : anchor);
      makeCellSample(cell, p, a, s);
      const double mean = squaredNorm(cell.centroid - p) + s.spreadPerPoint;
      if (!linearized)
      {
        forEachShellOfSpread(b, r2, mean, s.halfWidth, [&](int k, const ShellShare& share) { cellShare(k, s, share); });
        return;
      }
      // A linearized cell: its shares expanded at the far region's centre, moved to p's mean. With u = p - centre,
      // the mean moves by delta = |u|^2 - 2 a . u; the second-order term keeps (2 a . u)^2 / 2 of delta^2 / 2.
      const double centreMean = squaredNorm(a) + s.spreadPerPoint;
      const double delta = mean - centreMean;
      const double au = dot(a, p - centre);
      forEachShellOfSpreadExpanded(b, r2, centreMean, s.halfWidth, [&](int k, const ShellShareExpansion& e) {
        cellShare(k, s, movedShare(e, delta, 2.0 * au * au));
      });
    },
    [&](std::uint32_t i) {
      const Vec3 x = v.points.position(i) - p;
      const double d2 = squaredNorm(x);
      if (d2 < r2)
      {
        point(firstScaleHolding(b, d2), x, d2, v.points.normal(i));
      }
    });
}

/// Fits every scale of the evaluation point p from the multi-resolution samples of the ball of the largest scale
/// (forEachMultiresolutionTerm): points inside the ball enter exactly, as in evaluateAllScales; a cell taken whole
/// enters as its CellSample. b: the S increasing scales and their binning table; cells: the moment set's cell sums
/// (cellMoments); bins: S scratch moment sets; out: S samples.
template <typename Set>
GLS_INLINE void evaluateAllScalesMultiresolution(const MultiresolutionView& v, const typename Set::Cell* cells,
  const Vec3& p, const ScaleBinning& b, double minNeighbors, AggregateMomentsT<Set>* bins, typename Set::Sample* out)
{
  if (b.count <= 0)
  {
    return;
  }
  for (int k = 0; k < b.count; ++k)
  {
    clearMoments(bins[k]);
  }
  forEachMultiresolutionTerm<Set>(
    v, cells, p, b,
    [&](int k, const CellSampleT<Set>& s, const ShellShare& share) { addCellShare(bins[k], s, share); },
    [&](int k, const Vec3& x, double d2, const Vec3& n) { addPoint(bins[k], x, d2, n); });
  fitAllScalesFromBins(b, minNeighbors, bins, out);
}

/// The oriented sphere's evaluateAllScalesMultiresolution, from the pyramid's own cell sums.
GLS_INLINE void evaluateAllScalesMultiresolution(const MultiresolutionView& v, const Vec3& p, const ScaleBinning& b,
  double minNeighbors, AggregateMoments* bins, ScaleSample* out)
{
  evaluateAllScalesMultiresolution<OrientedSphereMoments>(v, v.cells, p, b, minNeighbors, bins, out);
}

/// evaluateAllScalesMultiresolution, bit for bit, with the scales taken G at a time (fitAllScalesByWindows): the
/// walk of the largest ball is repeated per window (the same terms in the same order), and only the window's bins
/// are added to. No scratch bins: the CUDA kernel's loop, where S bins per thread in memory are read and written
/// scattered. Set: the moment set; cells: its cell sums (cellMoments).
template <int G, typename Set>
GLS_INLINE void evaluateAllScalesMultiresolutionByWindows(const MultiresolutionView& v,
  const typename Set::Cell* cells, const Vec3& p, const ScaleBinning& b, double minNeighbors,
  typename Set::Sample* out)
{
  if (b.count <= 0)
  {
    return;
  }
  using Layout = AggregateMomentsT<Set>;
  fitAllScalesByWindows<G, Layout>(b, minNeighbors,
    [&](int k0, int, Layout* window) {
      forEachMultiresolutionTerm<Set>(
        v, cells, p, b,
        [&](int k, const CellSampleT<Set>& s, const ShellShare& share) {
          addToWindowSlot<G>(window, k - k0, [&](Layout& m) { addCellShare(m, s, share); });
        },
        [&](int k, const Vec3& x, double d2, const Vec3& n) {
          addToWindowSlot<G>(window, k - k0, [&](Layout& m) { addPoint(m, x, d2, n); });
        });
    },
    out);
}

/// The oriented sphere's evaluateAllScalesMultiresolutionByWindows, from the pyramid's own cell sums.
template <int G>
GLS_INLINE void evaluateAllScalesMultiresolutionByWindows(
  const MultiresolutionView& v, const Vec3& p, const ScaleBinning& b, double minNeighbors, ScaleSample* out)
{
  evaluateAllScalesMultiresolutionByWindows<G, OrientedSphereMoments>(v, v.cells, p, b, minNeighbors, out);
}

} // namespace gls
