// The pyramid's sorted points as it stores them (host/device): in single precision where every admitted coordinate is
// a float exactly (a float32 cloud, as scanners' files are: 12 bytes a point instead of 24), in double precision
// otherwise. Either way a read gives the same doubles, bit for bit, so the samples do not depend on the storage
// (tested), and a spatial tile or a distributed piece may store its points otherwise than the whole cloud does. The
// unit normals stay doubles: normalizing float normals when read cost 17% of the multi-resolution pass (measured at
// 1M points, 2 threads: 15.1 / 14.6 s against 12.8 / 12.5 s), and rounding the unit normals would lose the pass's
// exactness on spheres and planes.
#pragma once

#include "gls/HostDevice.h"
#include "gls/Vec3.h"

#include <cstddef>
#include <cstdint>

namespace gls
{

/// Whether v is a float exactly (converting it to float and back gives v; never so for NaN).
GLS_INLINE bool isFloatExact(double v)
{
  return static_cast<double>(static_cast<float>(v)) == v;
}

/// Whether every admitted point's 3 values (admit[i] != 0) are floats exactly: the test for storing them as floats.
/// On up to `threads` threads (0: every hardware thread).
bool admittedAreFloatExact(const double* values, std::size_t n, const unsigned char* admit, int threads);

/// The sorted points (`positions` as doubles, or `positions32` as floats, 3 a point) and their unit normals.
struct StoredPoints
{
  const Vec3* positions = nullptr;
  const float* positions32 = nullptr;
  const Vec3* normals = nullptr;

  GLS_INLINE Vec3 position(std::uint64_t i) const
  {
    if (this->positions32)
    {
      const float* f = this->positions32 + 3 * i;
      return { f[0], f[1], f[2] };
    }
    return this->positions[i];
  }

  /// The unit normal of point i.
  GLS_INLINE const Vec3& normal(std::uint64_t i) const { return this->normals[i]; }
};

} // namespace gls
