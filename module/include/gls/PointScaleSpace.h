// The per-point kernels, host/device: all scales of one evaluation point from one gather of its neighbours (the
// moment formulation), and the straightforward per-scale evaluation (one ball query and one weighted fit per scale)
// that serves as the second implementation in tests and as the baseline in benchmarks.
#pragma once

#include "gls/GridView.h"
#include "gls/MomentBins.h"
#include "gls/SphereFit.h"

namespace gls
{

/// The sampled scales and a lookup table that bins a squared distance without a data-dependent binary search:
/// table[j] is the first scale k with squaredScales[k] > j * cellWidth, so the scale of d2 is found from
/// table[floor(d2 / cellWidth)] by a short forward scan (usually zero or one step).
struct ScaleBinning
{
  const double* scales = nullptr;
  const double* squaredScales = nullptr;
  int count = 0;
  const int* table = nullptr;
  int tableSize = 0;
  double inverseCellWidth = 0.0; ///< tableSize / squaredScales[count - 1]
};

/// Reference form of firstScaleHolding: binary search (used to build and test the table).
GLS_INLINE int firstScaleHoldingBySearch(const double* squaredScales, int count, double d2)
{
  int lo = 0, hi = count - 1; // invariant: the answer is in [lo, hi]
  while (lo < hi)
  {
    const int mid = (lo + hi) / 2;
    if (d2 < squaredScales[mid])
    {
      hi = mid;
    }
    else
    {
      lo = mid + 1;
    }
  }
  return lo;
}

/// Index of the first scale whose open ball holds a neighbour at squared distance d2 (d2 < squaredScales[S-1]).
/// Exact whatever the rounding of the table index: the start is corrected backwards as well as forwards.
GLS_INLINE int firstScaleHolding(const ScaleBinning& b, double d2)
{
  const double u = d2 * b.inverseCellWidth;
  if (!(u >= 0.0 && u < static_cast<double>(b.tableSize)))
  {
    return firstScaleHoldingBySearch(b.squaredScales, b.count, d2); // degenerate scales (squares underflow)
  }
  int k = b.table[static_cast<int>(u)];
  while (k < b.count - 1 && !(d2 < b.squaredScales[k]))
  {
    ++k;
  }
  while (k > 0 && d2 < b.squaredScales[k - 1])
  {
    --k;
  }
  return k;
}

/// Fits every scale of the evaluation point p (any position; normally a data point) in one pass.
/// b: the S increasing scales and their binning table; bins: S scratch moment sets; out: S samples.
GLS_INLINE void evaluateAllScales(
  const GridView& g, const Vec3& p, const ScaleBinning& b, double minNeighbors, Moments* bins, ScaleSample* out)
{
  const int count = b.count;
  const double* scales = b.scales;
  for (int k = 0; k < count; ++k)
  {
    clearMoments(bins[k]);
  }
  forEachInBall(g, p, scales[count - 1], [&](std::uint64_t i, const Vec3& x, double d2) {
    addToMoments(bins[firstScaleHolding(b, d2)], x, g.normals[i]);
  });
  for (int k = 0; k < count; ++k)
  {
    if (k > 0)
    {
      addMoments(bins[k], bins[k - 1]);
    }
    WeightedSums s, ds;
    weightedSumsFromMoments(bins[k], scales[k], s, ds);
    out[k] = fitOrientedSphere(s, ds, neighborCount(bins[k]), minNeighbors);
  }
}

/// Fits one scale t of the evaluation point p directly: a ball query of radius t and the weighted sums.
GLS_INLINE ScaleSample evaluateOneScale(const GridView& g, const Vec3& p, double t, double minNeighbors)
{
  WeightedSums s, ds;
  double n = 0.0;
  forEachInBall(g, p, t, [&](std::uint64_t i, const Vec3& x, double d2) {
    accumulate(s, weightAt(d2, t), x, g.normals[i]);
    accumulate(ds, weightDerivativeAt(d2, t), x, g.normals[i]);
    n += 1.0;
  });
  return fitOrientedSphere(s, ds, n, minNeighbors);
}

} // namespace gls
