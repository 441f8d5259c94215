// The pyramid's sorted points as it stores them (host/device). Coordinates: in single precision where every admitted
// coordinate is a float exactly (a float32 cloud, as scanners' files are: 12 bytes a point instead of 24), in double
// precision otherwise. Normals: as unit normals in doubles, or, when asked (compact normals) and every admitted
// normal is a float exactly (the main job's, written by GLS Normal Estimation in float32), as given in floats and
// normalized when read (12 bytes a point instead of 24, for a longer pass). Either way a read gives the same doubles,
// bit for bit, so the samples do not depend on the storage (tested), and a spatial tile or a distributed piece may
// store its points otherwise than the whole cloud does.
#pragma once

#include "gls/HostDevice.h"
#include "gls/Numeric.h"
#include "gls/Vec3.h"

#include <cstddef>
#include <cstdint>

namespace gls
{

/// Whether v is a float exactly (within the floats' range, and converting it to float and back gives v; never so for
/// NaN or an infinity; no value out of range is converted, which C++ leaves undefined).
GLS_INLINE bool isFloatExact(double v)
{
  constexpr double largest = 3.4028234663852886e38; // FLT_MAX
  return v >= -largest && v <= largest && static_cast<double>(static_cast<float>(v)) == v;
}

/// Whether every admitted point's 3 values (admit[i] != 0) are floats exactly: the test for storing them as floats.
/// On up to `threads` threads (0: every hardware thread).
bool admittedAreFloatExact(const double* values, std::size_t n, const unsigned char* admit, int threads);

/// The sorted points (`positions` as doubles, or `positions32` as floats, 3 a point) and their unit normals
/// (`normals`, or `normals32`: the normals as given, 3 floats a point, each of finite non-zero length).
struct StoredPoints
{
  const Vec3* positions = nullptr;
  const float* positions32 = nullptr;
  const Vec3* normals = nullptr;
  const float* normals32 = nullptr;

  GLS_INLINE Vec3 position(std::uint64_t i) const
  {
    if (this->positions32)
    {
      const float* f = this->positions32 + 3 * i;
      return { f[0], f[1], f[2] };
    }
    return this->positions[i];
  }

  /// The unit normal of point i (unitNormal's, NeighborGrid.h).
  GLS_INLINE Vec3 normal(std::uint64_t i) const
  {
    if (this->normals32)
    {
      const float* f = this->normals32 + 3 * i;
      const double x = f[0], y = f[1], z = f[2];
      const double len = squareRoot(roundedSquaredLength(x, y, z));
      return { x / len, y / len, z / len };
    }
    return this->normals[i];
  }
};

} // namespace gls
