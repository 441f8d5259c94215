// LAS files (ASPRS LAS 1.0 to 1.4, point data record formats 0 to 10), the format aerial and most terrestrial lidar
// is delivered in: the header and variable-length records checked against the file, then the points decoded into
// plain arrays (positions in double precision: X scale + offset). LAZ (compressed LAS) is recognised and refused.
#pragma once

#include <cstddef>
#include <cstdint>
#include <istream>
#include <string>
#include <vector>

namespace gls
{

/// A per-point value stored after the standard fields, described by the Extra Bytes record (LASF_Spec, id 4).
struct LasExtraBytes
{
  std::string name;
  int dataType = 0;        ///< 1..10: u8, i8, u16, i16, u32, i32, u64, i64, f32, f64
  std::size_t offset = 0;  ///< in the point record
  double scale = 1.0;      ///< applied when the descriptor says so (options bit 3), else 1
  double shift = 0.0;      ///< likewise (options bit 4), else 0
};

struct LasHeader
{
  int versionMajor = 1, versionMinor = 0;
  int format = 0;                   ///< point data record format, 0..10
  std::size_t recordLength = 0;     ///< bytes per point record (at least the format's)
  std::uint64_t pointCount = 0;
  std::uint64_t pointOffset = 0;    ///< where the point records begin
  double scale[3] = { 1, 1, 1 }, offset[3] = { 0, 0, 0 };
  double min[3] = { 0, 0, 0 }, max[3] = { 0, 0, 0 }; ///< the header's bounds
  std::vector<LasExtraBytes> extra;

  bool hasGpsTime() const { return this->format == 1 || this->format >= 3; }
  bool hasRgb() const { return this->format == 2 || this->format == 3 || this->format == 5 || this->format >= 7; }
  bool hasNir() const { return this->format == 8 || this->format == 10; }
  bool extended() const { return this->format >= 6; } ///< formats 6-10: 4-bit returns, 16-bit scan angle
};

/// The size of a point record of each format (the standard fields only).
std::size_t lasFormatSize(int format);

/// Reads the header and the variable-length records of a LAS file of `fileSize` bytes. False with `error` saying what
/// is wrong: not a LAS file, LAZ, an unknown version or format, a record length below the format's, the point records
/// past the end of the file (truncated), an Extra Bytes record that does not fit the records.
bool readLasHeader(std::istream& in, std::uint64_t fileSize, LasHeader& header, std::string& error);

/// Where the points go: arrays of header.pointCount values (3 per point for xyz, rgb), null for what is not wanted
/// or not in the format.
struct LasColumns
{
  double* xyz = nullptr;                  ///< X * scale + offset, and so on (double precision)
  std::uint16_t* intensity = nullptr;
  std::uint8_t* returnNumber = nullptr;
  std::uint8_t* numberOfReturns = nullptr;
  std::uint8_t* classification = nullptr; ///< formats 0-5: the low 5 bits (the class); 6-10: the whole byte
  float* scanAngle = nullptr;             ///< degrees (formats 6-10: the stored value times 0.006)
  std::uint8_t* userData = nullptr;
  std::uint16_t* pointSourceId = nullptr;
  double* gpsTime = nullptr;
  std::uint16_t* rgb = nullptr;
  std::uint16_t* nir = nullptr;
  std::vector<double*> extra;             ///< one per header.extra, scaled and shifted
};

/// Decodes the point records (in blocks, so that the file is never held whole), then checks them against the header's
/// bounds (a point outside them by more than a scale step means an inconsistent file). False with `error`.
bool readLasPoints(std::istream& in, const LasHeader& header, LasColumns& columns, std::string& error);

} // namespace gls
