// The one-pass moment formulation (docs/math.md, "All scales in one pass"). Inside the ball, w = 1 - 2 d^2/t^2 +
// d^4/t^4 and dw/dt = 4 d^2/t^3 - 4 d^4/t^5, so every weighted sum at scale t is a combination of the un-weighted
// moments A_k(t) = sum_{d_i < t} d_i^(2k) f_i, k = 0, 1, 2, of the fitted values f_i (MomentSet.h). The last value,
// |x_i|^2, is d_i^2 for a point, so its moments are those of the others' d^2 and d^4 plus sum d^6: 25 distinct sums for
// the oriented sphere's nine values (a moment set's last value is always |x|^2). A set's omega-values (the kOmegaValues
// before |x|^2, weighted by the spatial derivative's omega = (4/t^2)(1 - d^2/t^2) only) keep A_0 and A_1 alone. A
// neighbour is added once, into the bin of the first scale whose open ball holds it; a running sum over the bins gives
// A_k at every scale.
#pragma once

#include "gls/MomentSet.h"

namespace gls
{

/// The moments of one bin (or, after the prefix sum, of one ball) of a moment set S (MomentSet.h): m[k * kValues + j]
/// = sum d^(2k) f_j for every value but the last, |x|^2 (k = 2 only for the kWeighted first ones: the omega-values
/// keep k = 0, 1), and m[kSixthPower] = sum d^6. The sums of |x|^2 d^(2k) are m[kValues], m[2 kValues] and
/// m[kSixthPower] (|x|^2 = d^2), so they are not stored twice. For the oriented sphere, eight values per power: one
/// 512-bit or two 256-bit vectors.
template <typename S>
struct alignas(64) MomentsT
{
  using Set = S;
  static constexpr int kValues = S::kValues - 1;             ///< the values stored per power: all but |x|^2
  static constexpr int kWeighted = kValues - S::kOmegaValues; ///< those weighted by w and dw/dt (three powers)
  static constexpr int kSixthPower = 2 * kValues + kWeighted; ///< where sum d^6 (= sum d^4 |x|^2) is
  static constexpr int kCount = kSixthPower + 1;
  double m[wholeCacheLines(kCount)];
};

/// The oriented sphere's one-pass moments.
using Moments = MomentsT<OrientedSphereMoments>;

template <typename S>
GLS_INLINE void clearMoments(MomentsT<S>& a)
{
  for (int i = 0; i < MomentsT<S>::kCount; ++i)
  {
    a.m[i] = 0.0;
  }
}

/// Adds one neighbour with local position x, squared distance d2 = |x|^2 and normal n.
template <typename S>
GLS_INLINE void addToMoments(MomentsT<S>& a, const Vec3& x, double d2, const Vec3& n)
{
  constexpr int V = MomentsT<S>::kValues;
  double f[S::kValues];
  S::pointValues(x, d2, n, f);
  const double d4 = d2 * d2;
  for (int j = 0; j < V; ++j)
  {
    a.m[j] += f[j];
    a.m[V + j] += d2 * f[j];
    if (j < MomentsT<S>::kWeighted)
    {
      a.m[2 * V + j] += d4 * f[j];
    }
  }
  a.m[MomentsT<S>::kSixthPower] += d4 * d2;
}

/// a += b (used by the running sum over scale bins).
template <typename S>
GLS_INLINE void addMoments(MomentsT<S>& a, const MomentsT<S>& b)
{
  for (int i = 0; i < MomentsT<S>::kCount; ++i)
  {
    a.m[i] += b.m[i];
  }
}

/// Number of neighbours in the ball the moments describe.
template <typename S>
GLS_INLINE double neighborCount(const MomentsT<S>& a)
{
  return a.m[0];
}

/// The weight as a polynomial in d^2 at scale t: w = 1 + c1 d^2 + c2 d^4 and dw/dt = e1 d^2 + e2 d^4, and the
/// spatial derivative's omega = o0 + o1 d^2 (dw/dp = omega x), inside the ball. Shared by every moment layout, so that
/// the exact and the multi-resolution sums use the same coefficients.
struct WeightPolynomial
{
  double c1, c2, e1, e2, o0, o1;
};

GLS_INLINE WeightPolynomial weightPolynomial(double t)
{
  const double it2 = 1.0 / (t * t);
  const double it4 = it2 * it2;
  return { -2.0 * it2, it4, 4.0 * it2 / t, -4.0 * it4 / t, 4.0 * it2, -4.0 * it4 };
}

/// Every value's sum weighted by w at scale t (v) and by dw/dt (dv), from the moments of the ball of radius t; an
/// omega-value's sum weighted by omega (v; its dv is 0).
template <typename S>
GLS_INLINE void weightedValues(const MomentsT<S>& a, double t, double* v, double* dv)
{
  constexpr int V = MomentsT<S>::kValues;
  const WeightPolynomial w = weightPolynomial(t);
  const double c0 = 1.0;
  for (int j = 0; j < MomentsT<S>::kWeighted; ++j)
  {
    const double a0 = a.m[j], a1 = a.m[V + j], a2 = a.m[2 * V + j];
    v[j] = c0 * a0 + w.c1 * a1 + w.c2 * a2;
    dv[j] = w.e1 * a1 + w.e2 * a2;
  }
  for (int j = MomentsT<S>::kWeighted; j < V; ++j)
  {
    v[j] = w.o0 * a.m[j] + w.o1 * a.m[V + j];
    dv[j] = 0.0;
  }
  // |x|^2 = d^2: its moments are sum d^2, sum d^4 and sum d^6.
  const double p0 = a.m[V], p1 = a.m[2 * V], p2 = a.m[MomentsT<S>::kSixthPower];
  v[V] = c0 * p0 + w.c1 * p1 + w.c2 * p2;
  dv[V] = w.e1 * p1 + w.e2 * p2;
}

/// The oriented sphere's weighted sums at scale t (s) and their t-derivatives (ds) from the moments of the ball.
GLS_INLINE void weightedSumsFromMoments(const Moments& a, double t, WeightedSums& s, WeightedSums& ds)
{
  double v[kFitValues], dv[kFitValues];
  weightedValues(a, t, v, dv);
  toWeightedSums(v, dv, s, ds);
}

} // namespace gls
