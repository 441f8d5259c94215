// LAS 1.4 files written from plain arrays: the points in point format 6, 7 (with colours) or 8 (with colours and
// near infrared), their lidar attributes where given (zero otherwise), every other per-point value as a float32 Extra
// Bytes field, and the coordinate system (WKT, or the GeoTIFF keys) as variable-length records. What
// gls::readLasHeader / readLasPoints read back, and what the specification's other readers read (ASPRS LAS 1.4 R15).
#pragma once

#include "gls/LasFile.h"

#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace gls
{

/// A per-point value written as float32 Extra Bytes fields, one per component (`name_x`, `name_y`, `name_z` for 3, or
/// `name_0`... for other counts), from floats or doubles (exactly one of the two pointers is set).
struct LasExtraSource
{
  std::string name;        ///< at most 32 characters with its suffix (longer: cut, the suffix kept)
  std::string description; ///< at most 32 characters (longer: cut)
  int components = 1;
  const float* floats = nullptr;
  const double* doubles = nullptr;
};

/// What a LAS file is written from: n points (3 doubles each; a point with a non-finite coordinate is not written),
/// their scale and offset (a position is written as round((x - offset) / scale), a 32-bit integer), and per point,
/// where given, the attributes of a LAS file (LasAttributesT: null gives 0, or one return of one).
struct LasWriteSource : LasAttributesT<true>
{
  std::size_t n = 0;
  const double* xyz = nullptr;
  double scale[3] = { 0.001, 0.001, 0.001 }, offset[3] = { 0.0, 0.0, 0.0 };
  std::vector<LasExtraSource> extra;
  LasCoordinateSystem coordinateSystem;
  std::string software = "GrowingLeastSquares";
};

/// What a write did.
struct LasWriteResult
{
  std::uint64_t written = 0;  ///< points written
  std::uint64_t leftOut = 0;  ///< points with a non-finite coordinate, not written
  int format = 6;             ///< the point format chosen (6, 7 or 8)
};

/// Writes a LAS 1.4 file. False with `error` when a position does not fit the 32-bit integers at its scale (say
/// which, and the scale that would), a scale is not positive and finite, or the stream fails.
bool writeLas(std::ostream& out, const LasWriteSource& source, LasWriteResult& result, std::string& error);

/// Whether every finite position of the n points is a 32-bit integer at the scale from the offset (a point set read
/// from a LAS file and then moved may not be).
bool lasIntegersHold(const double* xyz, std::size_t n, const double scale[3], const double offset[3]);

/// The scale and offset of positions that come from no LAS file: per axis the offset is the lowest finite
/// coordinate, the scale the finest power of ten whose integers hold the extent (2^31 - 1 steps), so a position moves
/// by at most half of it: 5e-11 on a 0.2 m object, 5e-7 on a 1 km survey tile. False
/// when no point has finite coordinates.
bool chooseLasScaleAndOffset(const double* xyz, std::size_t n, double scale[3], double offset[3]);

} // namespace gls
