// Small host/device numeric helpers: NaN, sqrt, floor and finiteness for any floating type.
#pragma once

#include "gls/HostDevice.h"

#include <cmath>
#include <limits>

namespace gls
{

template <typename T>
GLS_INLINE T quietNaN()
{
#if defined(__CUDA_ARCH__)
  return T(::nan(""));
#else
  return std::numeric_limits<T>::quiet_NaN();
#endif
}

template <typename T>
GLS_INLINE T squareRoot(T v)
{
  using std::sqrt;
  return sqrt(v);
}

/// x x + y y + z z with each product and each sum rounded once, left to right (never a fused multiply-add, whatever
/// the compiler contracts around it: the CPU kernels' AVX2+FMA builds, the device): the squared length every unit
/// normal is formed from, so that a normal normalized once and one normalized when read are the same bits.
GLS_INLINE double roundedSquaredLength(double x, double y, double z)
{
#if defined(__CUDA_ARCH__)
  return __dadd_rn(__dadd_rn(__dmul_rn(x, x), __dmul_rn(y, y)), __dmul_rn(z, z));
#else
  volatile double xx = x * x, yy = y * y, zz = z * z; // each product stored, so none is fused into the sums
  return xx + yy + zz;
#endif
}

/// The largest integer at or below v (as a T).
template <typename T>
GLS_INLINE T roundDown(T v)
{
  using std::floor;
  return floor(v);
}

template <typename T>
GLS_INLINE T absolute(T v)
{
  return v < T(0) ? -v : v;
}

template <typename T>
GLS_INLINE bool isFinite(T v)
{
  // NaN fails both comparisons; infinities fail the bound.
  return v == v && absolute(v) <= std::numeric_limits<T>::max();
}

/// Whether the three coordinates of a point are finite.
GLS_INLINE bool isFinitePoint(const double* p)
{
  return isFinite(p[0]) && isFinite(p[1]) && isFinite(p[2]);
}

} // namespace gls
