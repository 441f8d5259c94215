// The moments of the multi-resolution pass (docs/math.md, "Multi-resolution evaluation"): the exact pass's
// A_k = sum d^(2k) f for k = 0, 1, 2, where a sample is either one point or a whole cell of points (CellMoments.h:
// its points weighted by a linear field across the cell and binned by a spread of squared distances). Because
// |x|^2 of a cell's points is no longer its weight's d^2, every fitted value f of the moment set (MomentSet.h) is
// stored.
#pragma once

#include "gls/MomentBins.h"
#include "gls/MomentSet.h"

namespace gls
{

/// m[k * kStride + j] = sum over the samples of d^(2k) f_j (k = 0, 1, 2) for every value of the moment set S (its
/// omega-values too: their third moment is not read). Padded to whole 64-byte lines.
template <typename S>
struct alignas(64) AggregateMomentsT
{
  using Set = S;
  static constexpr int kValues = S::kValues;
  static constexpr int kWeighted = kValues - 1 - S::kOmegaValues; ///< the values before the omega-values
  /// Where each moment's row starts: a set with omega-values pads its rows to whole four-double vectors (so that the
  /// CPU kernel's vector adds never straddle a cache line; the padding stays 0); the oriented sphere's rows are
  /// packed, as they always were.
  static constexpr int kStride = S::kOmegaValues == 0 ? kValues : (kValues + 3) / 4 * 4;
  double m[wholeCacheLines(3 * kStride)];
};

/// The oriented sphere's multi-resolution moments.
using AggregateMoments = AggregateMomentsT<OrientedSphereMoments>;

template <typename S>
GLS_INLINE void clearMoments(AggregateMomentsT<S>& a)
{
  for (int i = 0; i < 3 * AggregateMomentsT<S>::kStride; ++i)
  {
    a.m[i] = 0.0;
  }
}

template <typename S>
GLS_INLINE void addMoments(AggregateMomentsT<S>& a, const AggregateMomentsT<S>& b)
{
  for (int i = 0; i < 3 * AggregateMomentsT<S>::kStride; ++i)
  {
    a.m[i] += b.m[i];
  }
}

/// Number of points in the ball the moments describe (cells count all their points).
template <typename S>
GLS_INLINE double neighborCount(const AggregateMomentsT<S>& a)
{
  return a.m[0];
}

/// Adds the values f (MomentSet.h) of a sample whose points all sit at squared distance d2.
template <typename S>
GLS_INLINE void addSampleSums(AggregateMomentsT<S>& a, const double* f, double d2)
{
  constexpr int V = S::kValues, R = AggregateMomentsT<S>::kStride;
  const double d4 = d2 * d2;
  for (int j = 0; j < V; ++j)
  {
    a.m[j] += f[j];
    a.m[R + j] += d2 * f[j];
    a.m[2 * R + j] += d4 * f[j];
  }
}

/// Adds one point with local position x (d2 = |x|^2) and normal n: exactly what the exact pass adds.
template <typename S>
GLS_INLINE void addPoint(AggregateMomentsT<S>& a, const Vec3& x, double d2, const Vec3& n)
{
  double f[S::kValues];
  S::pointValues(x, d2, n, f);
  addSampleSums(a, f, d2);
}

/// Every value's sum weighted by w at scale t (v) and by dw/dt (dv), from the moments of the ball of radius t; an
/// omega-value's sum weighted by omega (v; its dv is 0), as MomentBins.h's.
template <typename S>
GLS_INLINE void weightedValues(const AggregateMomentsT<S>& a, double t, double* v, double* dv)
{
  constexpr int V = S::kValues, W = AggregateMomentsT<S>::kWeighted, R = AggregateMomentsT<S>::kStride;
  const WeightPolynomial w = weightPolynomial(t);
  const auto weighted = [&](int j) {
    const double a0 = a.m[j], a1 = a.m[R + j], a2 = a.m[2 * R + j];
    v[j] = a0 + w.c1 * a1 + w.c2 * a2;
    dv[j] = w.e1 * a1 + w.e2 * a2;
  };
  for (int j = 0; j < W; ++j)
  {
    weighted(j);
  }
  for (int j = W; j < V - 1; ++j)
  {
    v[j] = w.o0 * a.m[j] + w.o1 * a.m[R + j];
    dv[j] = 0.0;
  }
  weighted(V - 1); // |x|^2
}

/// The oriented sphere's weighted sums at scale t (s) and their t-derivatives (ds) from the moments of the ball.
GLS_INLINE void weightedSumsFromMoments(const AggregateMoments& a, double t, WeightedSums& s, WeightedSums& ds)
{
  double v[kFitValues], dv[kFitValues];
  weightedValues(a, t, v, dv);
  toWeightedSums(v, dv, s, ds);
}

} // namespace gls
