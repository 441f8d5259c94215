// The weighted sums of one neighbourhood at one scale (docs/math.md, "Weighted sums"), with the smooth compact weight
// w(d, t) = (d^2/t^2 - 1)^2 for d < t and its scale derivative dw/dt = 4 d^2/t^3 (1 - d^2/t^2).
#pragma once

#include "gls/Vec3.h"

namespace gls
{

template <typename T>
struct WeightedSumsT
{
  T W = T(0);          ///< sum w_i
  Vec3T<T> P{};        ///< sum w_i x_i (local coordinates x_i = q_i - p)
  Vec3T<T> N{};        ///< sum w_i n_i
  T PN = T(0);         ///< sum w_i (x_i . n_i)
  T PP = T(0);         ///< sum w_i |x_i|^2
};

using WeightedSums = WeightedSumsT<double>;

/// Weight of a neighbour at squared distance d2 for scale t (0 outside the open ball of radius t).
template <typename T>
GLS_INLINE T weightAt(T d2, T t)
{
  if (!(d2 < t * t))
  {
    return T(0);
  }
  const T r = d2 / (t * t) - T(1);
  return r * r;
}

/// d w / d t of a neighbour at squared distance d2 for scale t (0 outside the open ball).
template <typename T>
GLS_INLINE T weightDerivativeAt(T d2, T t)
{
  if (!(d2 < t * t))
  {
    return T(0);
  }
  return T(4) * d2 / (t * t * t) * (T(1) - d2 / (t * t));
}

/// Adds one neighbour (local position x, normal n) with weight w to the sums.
template <typename T>
GLS_INLINE void accumulate(WeightedSumsT<T>& s, T w, const Vec3T<T>& x, const Vec3T<T>& n)
{
  s.W += w;
  s.P = s.P + w * x;
  s.N = s.N + w * n;
  s.PN += w * dot(x, n);
  s.PP += w * squaredNorm(x);
}

} // namespace gls
