// A minimal 3-vector usable on host and device (no Eigen, no STL), templated on the scalar so that tests can run
// the same formulas in long double.
#pragma once

#include "gls/HostDevice.h"

namespace gls
{

template <typename T>
struct Vec3T
{
  T x, y, z;
};

using Vec3 = Vec3T<double>;

template <typename T>
GLS_INLINE Vec3T<T> operator+(const Vec3T<T>& a, const Vec3T<T>& b)
{
  return { a.x + b.x, a.y + b.y, a.z + b.z };
}

template <typename T>
GLS_INLINE Vec3T<T> operator-(const Vec3T<T>& a, const Vec3T<T>& b)
{
  return { a.x - b.x, a.y - b.y, a.z - b.z };
}

template <typename T>
GLS_INLINE Vec3T<T> operator*(T s, const Vec3T<T>& a)
{
  return { s * a.x, s * a.y, s * a.z };
}

template <typename T>
GLS_INLINE T dot(const Vec3T<T>& a, const Vec3T<T>& b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

template <typename T>
GLS_INLINE T squaredNorm(const Vec3T<T>& a)
{
  return dot(a, a);
}

template <typename T>
GLS_INLINE Vec3T<T> cross(const Vec3T<T>& a, const Vec3T<T>& b)
{
  return { a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x };
}

} // namespace gls
