// The one-pass moment formulation (docs/math.md, "All scales in one pass"). Inside the ball,
// w = 1 - 2 d^2/t^2 + d^4/t^4 and dw/dt = 4 d^2/t^3 - 4 d^4/t^5, so every weighted sum at scale t is a combination
// of the un-weighted moments A_k(t) = sum_{d_i < t} d_i^(2k) f_i, k = 0, 1, 2, of the nine values
// f_i = (1, x_i, n_i, x_i . n_i, |x_i|^2): 25 distinct sums, since |x_i|^2 = d_i^2. A neighbour is added once, into
// the bin of the first scale whose open ball holds it; a running sum over the bins gives A_k at every scale.
#pragma once

#include "gls/WeightedSums.h"

namespace gls
{

constexpr int kMomentValues = 8;                        ///< f = 1, x (3), n (3), x.n
constexpr int kMomentCount = 3 * kMomentValues + 1;     ///< k = 0, 1, 2, and sum d^6 (= sum d^4 |x|^2)

/// The 25 moments of one bin (or, after the prefix sum, of one ball): m[k * 8 + j] = sum d^(2k) f_j, and
/// m[24] = sum d^6. The sums of |x|^2 d^(2k) are m[8], m[16] and m[24] (|x|^2 = d^2), so they are not stored twice.
/// Eight values per power: one 512-bit or two 256-bit vectors.
struct alignas(64) Moments
{
  double m[kMomentCount + 7]; // padded to a whole number of 64-byte lines
};

GLS_INLINE void clearMoments(Moments& a)
{
  for (int i = 0; i < kMomentCount; ++i)
  {
    a.m[i] = 0.0;
  }
}

/// Adds one neighbour with local position x, squared distance d2 = |x|^2 and normal n.
GLS_INLINE void addToMoments(Moments& a, const Vec3& x, double d2, const Vec3& n)
{
  const double f[kMomentValues] = { 1.0, x.x, x.y, x.z, n.x, n.y, n.z, dot(x, n) };
  const double d4 = d2 * d2;
  for (int j = 0; j < kMomentValues; ++j)
  {
    a.m[j] += f[j];
    a.m[kMomentValues + j] += d2 * f[j];
    a.m[2 * kMomentValues + j] += d4 * f[j];
  }
  a.m[3 * kMomentValues] += d4 * d2;
}

/// a += b (used by the running sum over scale bins).
GLS_INLINE void addMoments(Moments& a, const Moments& b)
{
  for (int i = 0; i < kMomentCount; ++i)
  {
    a.m[i] += b.m[i];
  }
}

/// Number of neighbours in the ball the moments describe.
GLS_INLINE double neighborCount(const Moments& a)
{
  return a.m[0];
}

/// The weight as a polynomial in d^2 at scale t: w = 1 + c1 d^2 + c2 d^4 and dw/dt = e1 d^2 + e2 d^4 (inside the
/// ball). Shared by every moment layout, so that the exact and the multi-resolution sums use the same coefficients.
struct WeightPolynomial
{
  double c1, c2, e1, e2;
};

GLS_INLINE WeightPolynomial weightPolynomial(double t)
{
  const double it2 = 1.0 / (t * t);
  const double it4 = it2 * it2;
  return { -2.0 * it2, it4, 4.0 * it2 / t, -4.0 * it4 / t };
}

/// Writes the nine values (1, x, n, x.n, |x|^2) weighted by w (v) and by dw/dt (dv) into s and ds.
GLS_INLINE void assignWeightedSums(const double* v, const double* dv, WeightedSums& s, WeightedSums& ds)
{
  s.W = v[0];
  s.P = { v[1], v[2], v[3] };
  s.N = { v[4], v[5], v[6] };
  s.PN = v[7];
  s.PP = v[8];
  ds.W = dv[0];
  ds.P = { dv[1], dv[2], dv[3] };
  ds.N = { dv[4], dv[5], dv[6] };
  ds.PN = dv[7];
  ds.PP = dv[8];
}

/// Weighted sums at scale t (s) and their t-derivatives (ds) from the moments of the ball of radius t.
GLS_INLINE void weightedSumsFromMoments(const Moments& a, double t, WeightedSums& s, WeightedSums& ds)
{
  const WeightPolynomial w = weightPolynomial(t);
  const double c0 = 1.0;
  double v[kMomentValues + 1];
  double dv[kMomentValues + 1];
  for (int j = 0; j < kMomentValues; ++j)
  {
    const double a0 = a.m[j], a1 = a.m[kMomentValues + j], a2 = a.m[2 * kMomentValues + j];
    v[j] = c0 * a0 + w.c1 * a1 + w.c2 * a2;
    dv[j] = w.e1 * a1 + w.e2 * a2;
  }
  // |x|^2 = d^2: its moments are sum d^2, sum d^4 and sum d^6.
  const double p0 = a.m[kMomentValues], p1 = a.m[2 * kMomentValues], p2 = a.m[3 * kMomentValues];
  v[kMomentValues] = c0 * p0 + w.c1 * p1 + w.c2 * p2;
  dv[kMomentValues] = w.e1 * p1 + w.e2 * p2;
  assignWeightedSums(v, dv, s, ds);
}

} // namespace gls
