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

} // namespace gls
