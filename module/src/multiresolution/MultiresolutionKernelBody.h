// Private to the CPU multi-resolution kernel (MultiresolutionKernel.cpp, and the tests that run it with a moment set of
// their own): the kernel of MultiresolutionKernel.h for any moment set (MomentSet.h), one point at a time (evaluate):
// the walks of its walk region and far parts, reused while consecutive points share them (MultiresolutionWalk.h); their
// samples packed once per region, those inside the smallest scale's sphere for the whole region summed as a polynomial
// of p (MultiresolutionPacking.h); the far parts' linearized cells summed once per far region
// (MultiresolutionFarCells.h); then, for the point, its packed cells sorted by the number of shells their spread meets
// (MultiresolutionCellKinds.h), added whole or in pieces (MultiresolutionPieces.h, MultiresolutionSampleAdds.h), its
// points binned one by one, and a fit per scale from the running sum of the bins.
#pragma once

#include "gls/MultiresolutionKernel.h"

#include "KernelVectors.h"

#if GLS_KERNEL_VECTORS
// Four-double vectors pass between always-inlined helpers and lambdas only (KernelVectors.h), so the vector-argument
// ABI that -Wpsabi warns about never applies; lambda instances are reported at the end of the file, hence no pop (and
// the pragma comes before the kernel's private headers, whose lambdas it covers too).
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

#include "KernelBatches.h"
#include "MultiresolutionCellKinds.h"
#include "MultiresolutionFarCells.h"
#include "MultiresolutionPacking.h"
#include "MultiresolutionPieces.h"
#include "MultiresolutionSampleAdds.h"
#include "MultiresolutionWalk.h"

#include <cstring>

namespace gls
{
namespace multiresolution
{


/// Adds the packed cells for p. A cell within one shell (most cells near p) adds its wholeShare there; a cell whose
/// spread meets two or three shells adds as many pieces (addPieces), so that no kind branches on the cell; the few
/// cells that meet more shells add theirs in a loop of their own (calling forEachShellOfSpread there instead measured
/// 20% slower on the bunny at 300k points: 4.7 s against 3.7-3.9 s). Cells are first sorted into these kinds
/// without a branch (classifyCells), then each kind is added in a loop of its own; the shares and their order are
/// forEachShellOfSpread's.
template <bool Avx2, typename Set>
GLS_FORCE_INLINE void addPackedCells(const Vec3& p, const ScaleBinning& b, double r2, MultiresolutionScratchT<Set>& s,
  AggregateMomentsT<Set>* bins)
{
  const std::vector<PackedCellT<Set>>& cells = s.packedCells;
  const int S = b.count;
  const double* sq = b.squaredScales;
  const std::size_t n = cells.size();
  s.cellMean.resize(n);
  s.cellShell.resize(n);
  s.singleCells.resize(n + 4); // room for classifyCellsAvx2's whole-vector stores past the end
  s.pairCells.resize(n + 4);
  s.spreadCells.resize(n + 4);
  s.wideCells.resize(n + 4);
  kernel::CellKinds kinds{ s.cellMean.data(), s.cellShell.data(), s.singleCells.data(), s.pairCells.data(),
    s.spreadCells.data(), s.wideCells.data() };
  std::size_t classified = 0;
#if GLS_KERNEL_DISPATCH
  if constexpr (Avx2)
  {
    classified = kernel::classifyCellsAvx2(p, b, r2, s.placements, n, kinds);
  }
#endif
  kernel::classifyCells(p, b, r2, s.placements, classified, n, kinds);
  const std::size_t singles = kinds.singles, pairs = kinds.pairs, spreads = kinds.triples, wides = kinds.wides;
  for (std::size_t i = 0; i < singles; ++i)
  {
    const std::uint32_t c = s.singleCells[i];
    kernel::addPackedCellShare(
      bins[s.cellShell[c]], cells[c].sample, wholeShare(s.cellMean[c], s.placements.halfWidth[c]));
  }
#if GLS_KERNEL_DISPATCH
  if constexpr (Avx2)
  {
    kernel::addPiecesAvx2<2, Set>(b, r2, s.pairCells.data(), pairs, s, bins);
    kernel::addPiecesAvx2<3, Set>(b, r2, s.spreadCells.data(), spreads, s, bins);
  }
  else
#endif
  {
    kernel::addPieces<2, Set>(b, r2, s.pairCells.data(), pairs, s, bins);
    kernel::addPieces<3, Set>(b, r2, s.spreadCells.data(), spreads, s, bins);
  }
  for (std::size_t i = 0; i < wides; ++i)
  {
    // More shells (past three, so below the last one): pieces up to the shell holding min(hi, r2).
    const std::uint32_t c = s.wideCells[i];
    const CellSampleT<Set>& sample = cells[c].sample;
    const double mean = s.cellMean[c], a = s.placements.halfWidth[c];
    const SpreadDensity density = s.placements.density(c);
    const double top = mean + a < r2 ? mean + a : r2;
    double u = mean - a;
    for (int k = s.cellShell[c]; k < S && u < top; ++k)
    {
      const double v = sq[k] < top ? sq[k] : top;
      kernel::addPackedCellShare(bins[k], sample, pieceShare(mean, density, u, v));
      u = v;
    }
  }
}

/// Adds the packed samples of p's ball: the cells, each spread over the shells it meets (forEachShellOfSpread), and the
/// points inside it, binned by their distance from p.
template <bool Avx2, typename Set>
GLS_FORCE_INLINE void addPackedSamples(const Vec3& p, const ScaleBinning& b, double r2,
  MultiresolutionScratchT<Set>& s, AggregateMomentsT<Set>* bins)
{
  addPackedCells<Avx2>(p, b, r2, s, bins);
  const std::vector<PackedPointT<Set>>& points = s.packedPoints;
  kernel::addInsideBall(
    p, b, r2, std::size_t(0), points.size(), [](std::size_t c) { return c; },
    [&](std::size_t i) -> const Vec3& { return points[i].position; },
    [&](std::size_t i, double d2, int k) { kernel::addPackedSums(bins[k], points[i].sums, d2); });
}

/// Moves the moments from coordinates about o to coordinates about p (u = o - p; shiftValues for each power: the
/// weights d^(2k) stay p's).
template <typename Set>
GLS_FORCE_INLINE void shiftMoments(const Vec3& u, double uu, AggregateMomentsT<Set>& a)
{
  for (int j = 0; j < 3; ++j)
  {
    Set::shiftValues(u, uu, a.m + j * AggregateMomentsT<Set>::kStride);
  }
}

/// fitAllScalesFromBins for bins whose sums are about o (u = o - p): the running sum stays about o, and a copy of it
/// is moved to p for each scale's fit (shiftMoments). Moving the bins in memory first, then summing them, read back
/// values just stored piecewise (measured on the bunny at 1M points: 8.28 / 7.96 us per point against 7.93 / 7.75;
/// at 3M 7.73 against 7.19, rocker arm 7.10 against 6.96). A set with omega-values moves its weighted sums instead
/// (Set::shiftWeightedValues: two vectors of values instead of three rows of moments).
template <typename Set>
GLS_FORCE_INLINE void fitAllScalesAboutOrigin(const ScaleBinning& b, double minNeighbors,
  const AggregateMomentsT<Set>* bins, const Vec3& u, typename Set::Sample* out)
{
  const double uu = squaredNorm(u);
  AggregateMomentsT<Set> ball;
  clearMoments(ball);
  for (int k = 0; k < b.count; ++k)
  {
    addMoments(ball, bins[k]);
    if constexpr (Set::kOmegaValues > 0)
    {
      const double t = b.scales[k];
      double v[Set::kValues], dv[Set::kValues];
      weightedValues(ball, t, v, dv);
      Set::shiftWeightedValues(u, uu, t, v, dv);
      out[k] = Set::fit(v, dv, t, neighborCount(ball), minNeighbors);
    }
    else
    {
      AggregateMomentsT<Set> moved = ball;
      shiftMoments(u, uu, moved);
      out[k] = fitBall(moved, b.scales[k], minNeighbors);
    }
  }
}

template <bool Avx2, typename Set>
GLS_FORCE_INLINE void evaluate(const MultiresolutionView& v, const typename Set::Cell* cells, const Vec3& p,
  const ScaleBinning& b, double minNeighbors, MultiresolutionScratchT<Set>& s, typename Set::Sample* out)
{
  if (b.count <= 0)
  {
    return;
  }
  s.bins.resize(static_cast<std::size_t>(b.count));
  std::memset(static_cast<void*>(s.bins.data()), 0, sizeof(AggregateMomentsT<Set>) * s.bins.size()); // all 0.0
  const double r = b.scales[b.count - 1];
  const FarRule far = farRule(v, p);
  const WalkRegion region = walkRegion(v, p);
  // Every sum about the largest far region's corner (the walk region's without a far part), moved to p at the end.
  const Vec3 o = outermostRegion(far, region).corner;
  for (int i = 0; i < far.count; ++i)
  {
    const WalkKey key{ v.nodes, v.count, v.accuracy, r, b.scales[0], v.linearizedDistance, region, far.region[i],
      b.squaredScales, b.count };
    if (!s.farWalked[i] || !kernel::sameFarWalk(s.farKey[i], key))
    {
      // A new far region: its part's walk, summed once for its points (it reuses the walk's lists, not its packed
      // samples).
      kernel::walk(v, region, far, i + 1, false, r, key.smallest, s);
      kernel::packFarWalk<Set>(v, cells, far.region[i], i, o, b, r * r, s, s.linearized[i]);
      s.farWalked[i] = true;
      s.farKey[i] = key;
    }
  }
  const WalkKey key{ v.nodes, v.count, v.accuracy, r, b.scales[0], v.linearizedDistance, region,
    outermostRegion(far, region), b.squaredScales, b.count };
  if (!s.walked || !kernel::sameWalk(s.walkedKey, key))
  {
    kernel::walk(v, region, far, 0, far.count > 0, r, key.smallest, s);
    for (int i = 0; i < far.count; ++i)
    {
      // The far cells whose spread is too narrow to linearize (linearizable), sampled as near cells.
      s.taken.insert(s.taken.end(), s.farSampled[i].begin(), s.farSampled[i].end());
      s.takenLevel.insert(s.takenLevel.end(), s.farSampledLevel[i].begin(), s.farSampledLevel[i].end());
    }
    kernel::packWalk<Set>(v, cells, region, o, b.squaredScales[0], s);
    s.walked = true;
    s.walkedKey = key;
  }
  addPackedSamples<Avx2>(p, b, r * r, s, s.bins.data());
  kernel::addInnerSums(s.inner, p - regionCentre(region), s.bins[0]);
  for (int i = 0; i < far.count; ++i)
  {
    kernel::addLinearizedCells(s.linearized[i], p - regionCentre(far.region[i]), b.count, s.bins.data());
  }
  fitAllScalesAboutOrigin(b, minNeighbors, s.bins.data(), o - p, out);
}

template <typename Set>
void evaluateBaseline(const MultiresolutionView& v, const typename Set::Cell* cells, const Vec3& p,
  const ScaleBinning& b, double minNeighbors, MultiresolutionScratchT<Set>& s, typename Set::Sample* out)
{
  evaluate<false, Set>(v, cells, p, b, minNeighbors, s, out);
}

#if GLS_KERNEL_DISPATCH
template <typename Set>
__attribute__((target("avx2,fma"))) void evaluateAvx2(const MultiresolutionView& v, const typename Set::Cell* cells,
  const Vec3& p, const ScaleBinning& b, double minNeighbors, MultiresolutionScratchT<Set>& s,
  typename Set::Sample* out)
{
  evaluate<true, Set>(v, cells, p, b, minNeighbors, s, out);
}
#endif


/// evaluateAllScalesMultiresolutionOnCpu for the moment set Set, whose cell sums of the levels summedLevel and above
/// are `cells` (cellMoments).
template <typename Set>
void evaluateAllScalesMultiresolutionOnCpuFor(const MultiresolutionView& v, const typename Set::Cell* cells,
  const Vec3& p, const ScaleBinning& b, double minNeighbors, MultiresolutionScratchT<Set>& s,
  typename Set::Sample* out, CpuKernelBuild build)
{
#if GLS_KERNEL_DISPATCH
  if (build == CpuKernelBuild::Fastest && kernel::hasAvx2())
  {
    evaluateAvx2<Set>(v, cells, p, b, minNeighbors, s, out);
    return;
  }
#endif
  evaluateBaseline<Set>(v, cells, p, b, minNeighbors, s, out);
}

} // namespace multiresolution
} // namespace gls
