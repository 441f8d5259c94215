// The per-point kernels, host/device: all scales of one evaluation point from one gather of its neighbours (the
// moment formulation), and the straightforward per-scale evaluation (one ball query and one weighted fit per scale)
// that serves as the second implementation in tests and as the baseline in benchmarks.
#pragma once

#include "gls/GridView.h"
#include "gls/MomentBins.h"
#include "gls/SphereFit.h"

namespace gls
{

/// One cell of the binning table: the squared distances v with floor(v * inverseCellWidth) == j. `base` is the
/// number of squared scales whose own cell is before j (so all of them are below any v of the cell), `edge` the one
/// squared scale whose cell is j (+infinity if none). base = -1 marks a cell holding several squared scales, where
/// the lookup falls back to the binary search.
struct BinningCell
{
  double edge;
  int base;
  int unused;
};

/// The sampled scales and a lookup table that bins a squared distance without a data-dependent search: the first
/// scale whose open ball holds d2 is table[j].base + (d2 >= table[j].edge), j = floor(d2 * inverseCellWidth).
/// Exact: the cell index is a monotone function of d2, computed the same way when the table is built.
struct ScaleBinning
{
  const double* scales = nullptr;
  const double* squaredScales = nullptr;
  int count = 0;
  const BinningCell* table = nullptr;
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

/// Index of the first scale whose open ball holds a neighbour at squared distance d2 (d2 < squaredScales[S-1]):
/// one table load and one comparison, the binary search only for cells holding several scales.
GLS_INLINE int firstScaleHolding(const ScaleBinning& b, double d2)
{
  const double u = d2 * b.inverseCellWidth;
  if (!(u >= 0.0 && u < static_cast<double>(b.tableSize)))
  {
    return firstScaleHoldingBySearch(b.squaredScales, b.count, d2); // degenerate scales (squares underflow)
  }
  const BinningCell cell = b.table[static_cast<int>(u)];
  if (cell.base < 0)
  {
    return firstScaleHoldingBySearch(b.squaredScales, b.count, d2);
  }
  const int k = cell.base + (d2 >= cell.edge ? 1 : 0);
  return k < b.count - 1 ? k : b.count - 1;
}

/// The sample a layout's fit gives (Moments or AggregateMoments of a moment set S: S::Sample).
template <typename Layout>
using SampleOf = typename Layout::Set::Sample;

/// The fit of the ball of scale t from its moments (about the evaluation point): the moment set's fit of its
/// weighted values. Inlined into its caller (the CPU kernels' AVX2 builds fit the principal curvatures' set so:
/// fitAllScalesFromBinsInlined, src/KernelSetCalls.h); fitBall is the same, left to the compiler.
template <typename Layout>
GLS_FORCE_INLINE SampleOf<Layout> fitBallInlined(const Layout& ball, double t, double minNeighbors)
{
  using S = typename Layout::Set;
  double v[S::kValues], dv[S::kValues];
  weightedValues(ball, t, v, dv);
  return S::fit(v, dv, t, neighborCount(ball), minNeighbors);
}

template <typename Layout>
GLS_INLINE SampleOf<Layout> fitBall(const Layout& ball, double t, double minNeighbors)
{
  return fitBallInlined(ball, t, minNeighbors);
}

/// One step of the running sum over the bins: ball += bin, the ball of scale t, and its fit.
template <typename Layout>
GLS_INLINE SampleOf<Layout> addBinAndFit(Layout& ball, const Layout& bin, double t, double minNeighbors)
{
  addMoments(ball, bin);
  return fitBall(ball, t, minNeighbors);
}

/// Turns the S bins of one evaluation point into its S samples: a running sum over the bins gives the moments of
/// the ball of each scales[k] (the bins are left as they are), and one fit per scale. Layout is MomentsT (the exact
/// pass) or AggregateMomentsT (the multi-resolution pass) of a moment set: both give clearMoments, addMoments,
/// weightedValues and neighborCount.
template <typename Layout>
GLS_FORCE_INLINE void fitAllScalesFromBinsInlined(
  const ScaleBinning& b, double minNeighbors, const Layout* bins, SampleOf<Layout>* out)
{
  Layout ball;
  clearMoments(ball);
  for (int k = 0; k < b.count; ++k)
  {
    addMoments(ball, bins[k]);
    out[k] = fitBallInlined(ball, b.scales[k], minNeighbors);
  }
}

template <typename Layout>
GLS_INLINE void fitAllScalesFromBins(
  const ScaleBinning& b, double minNeighbors, const Layout* bins, SampleOf<Layout>* out)
{
  fitAllScalesFromBinsInlined(b, minNeighbors, bins, out);
}

/// Calls add(window[slot]) when 0 <= slot < G: a window's bins are indexed by constants only, so that a GPU keeps
/// them in registers (an index known at run time would put them in local memory).
template <int G, typename Layout, typename Add>
GLS_INLINE void addToWindowSlot(Layout* window, int slot, Add&& add)
{
#if defined(__CUDACC__)
#pragma unroll
#endif
  for (int w = 0; w < G; ++w)
  {
    if (w == slot)
    {
      add(window[w]);
    }
  }
}

/// fitAllScalesFromBins with the scales taken G at a time, without S scratch bins in memory: for each window of
/// scales [k0, top], gather(k0, top, window) adds to window[k - k0] exactly what the one pass adds to bins[k] (the
/// same terms in the same order), and the window's scales are fitted from the running sum before the next window.
/// The samples are bitwise those of fitAllScalesFromBins. The CUDA kernels' form: a GPU thread has no room for S
/// bins in registers, and S bins per thread in global memory are read and written scattered (docs/performance.md).
template <int G, typename Layout, typename Gather>
GLS_INLINE void fitAllScalesByWindows(
  const ScaleBinning& b, double minNeighbors, Gather&& gather, SampleOf<Layout>* out)
{
  Layout ball;
  clearMoments(ball);
  for (int k0 = 0; k0 < b.count; k0 += G)
  {
    const int top = (k0 + G < b.count ? k0 + G : b.count) - 1;
    Layout window[G];
#if defined(__CUDACC__)
#pragma unroll
#endif
    for (int w = 0; w < G; ++w)
    {
      clearMoments(window[w]);
    }
    gather(k0, top, window);
#if defined(__CUDACC__)
#pragma unroll
#endif
    for (int w = 0; w < G; ++w)
    {
      const int k = k0 + w;
      if (k <= top)
      {
        out[k] = addBinAndFit(ball, window[w], b.scales[k], minNeighbors);
      }
    }
  }
}

/// evaluateAllScales, bit for bit, with the scales taken G at a time (fitAllScalesByWindows): one ball query of the
/// window's largest scale per window, keeping the neighbours whose first scale is in the window. The ball of a
/// smaller radius is walked in the same order (rows by z, then y, points in grid order), so each bin receives the
/// same neighbours in the same order. About sum_k (t_k / t_max)^2 / G times the neighbours of one largest ball are
/// visited (each a distance test), against one ball with S bins in memory. No scratch: the CUDA kernel's loop.
/// Set: the moment set (MomentSet.h).
template <int G, typename Set = OrientedSphereMoments>
GLS_INLINE void evaluateAllScalesByWindows(
  const GridView& g, const Vec3& p, const ScaleBinning& b, double minNeighbors, typename Set::Sample* out)
{
  if (b.count <= 0)
  {
    return;
  }
  fitAllScalesByWindows<G, MomentsT<Set>>(b, minNeighbors,
    [&](int k0, int top, MomentsT<Set>* window) {
      const double below = k0 > 0 ? b.squaredScales[k0 - 1] : 0.0; // nearer neighbours are an earlier window's
      forEachInBall(g, p, b.scales[top], [&](std::uint64_t i, const Vec3& x, double d2) {
        if (d2 >= below)
        {
          addToWindowSlot<G>(window, firstScaleHolding(b, d2) - k0,
            [&](MomentsT<Set>& m) { addToMoments(m, x, d2, g.normals[i]); });
        }
      });
    },
    out);
}

/// Fits every scale of the evaluation point p (any position; normally a data point) in one pass.
/// b: the S increasing scales and their binning table; bins: S scratch moment sets; out: S samples.
/// The reference host/device loop: the CUDA kernel runs its windowed form (evaluateAllScalesByWindows, bitwise the
/// same samples); the CPU engine runs the batched form of the same arithmetic (OnePassKernel.h). Set: the moment set
/// (MomentSet.h), the oriented sphere's for Moments.
template <typename Set>
GLS_INLINE void evaluateAllScales(const GridView& g, const Vec3& p, const ScaleBinning& b, double minNeighbors,
  MomentsT<Set>* bins, typename Set::Sample* out)
{
  if (b.count <= 0)
  {
    return;
  }
  for (int k = 0; k < b.count; ++k)
  {
    clearMoments(bins[k]);
  }
  forEachInBall(g, p, b.scales[b.count - 1], [&](std::uint64_t i, const Vec3& x, double d2) {
    addToMoments(bins[firstScaleHolding(b, d2)], x, d2, g.normals[i]);
  });
  fitAllScalesFromBins(b, minNeighbors, bins, out);
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
