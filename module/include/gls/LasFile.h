// LAS files (ASPRS LAS 1.0 to 1.4, point data record formats 0 to 10), the format aerial and most terrestrial lidar
// is delivered in: the header and variable-length records checked against the file, then the points decoded into
// plain arrays (positions in double precision: X scale + offset, so that a position is the file's integer exactly).
// The coordinate system (OGC WKT, or the GeoTIFF keys) is read from the records and the extended records of LAS 1.4.
// Common quirks of real writers are read with a note naming each (LasHeader::quirks, LasReadResult::quirks): Extra
// Bytes descriptors of the deprecated array types, bytes at the end of each record that no descriptor describes, a
// header whose bounds are stored unscaled, a LAS 1.4 point count in the legacy field only. LAZ (compressed LAS) is
// recognised and refused.
#pragma once

#include <cstddef>
#include <cstdint>
#include <istream>
#include <string>
#include <type_traits>
#include <vector>

namespace gls
{

/// A per-point value stored after the standard fields, described by the Extra Bytes record (LASF_Spec, id 4).
struct LasExtraBytes
{
  std::string name;
  int dataType = 0;        ///< 1..10: u8, i8, u16, i16, u32, i32, u64, i64, f32, f64 (of each component)
  int components = 1;      ///< 1; 2 or 3 for the deprecated array types 11-20 and 21-30 (read with a quirk note)
  std::size_t offset = 0;  ///< in the point record
  double scale[3] = { 1.0, 1.0, 1.0 }; ///< applied when the descriptor says so (options bit 3), else 1
  double shift[3] = { 0.0, 0.0, 0.0 }; ///< likewise (options bit 4), else 0
};

/// The coordinate system of a LAS file's positions, as its (extended) variable-length records give it
/// (LASF_Projection): OGC WKT (record 2112), or the GeoTIFF keys (34735, with 34736 and 34737), or both.
struct LasCoordinateSystem
{
  std::string wkt;                        ///< OGC coordinate system WKT, or empty
  std::vector<std::uint16_t> geoKeys;     ///< GeoKeyDirectoryTag (4 values a key, after a 4-value header), or empty
  std::vector<double> geoDoubles;         ///< GeoDoubleParamsTag
  std::string geoAscii;                   ///< GeoAsciiParamsTag ('|' separates its strings)

  bool empty() const { return this->wkt.empty() && this->geoKeys.empty(); }
};

/// Where the fields after the position (12 bytes of X Y Z) and the intensity (2) lie in a point record of a format
/// (bytes from the record's start; -1: not in the format), as LAS 1.4 R15's tables 7-17 place them. Formats 0-5: the
/// returns byte (return number, number of returns, scan direction, edge of flight line), the classification byte
/// (the class in 5 bits, synthetic, key-point, withheld), an 8-bit scan angle rank; formats 6-10: 4-bit returns, a
/// flags byte (synthetic, key-point, withheld, overlap, the scanner channel, scan direction, edge of flight line), a
/// whole classification byte and a 16-bit scan angle in steps of 0.006 degree.
struct LasRecordLayout
{
  bool extended = false;
  int returns = 14, flags = 15, classification = 15, scanAngle = 16, userData = 17, pointSourceId = 18;
  int gpsTime = -1, rgb = -1, nir = -1;
};
LasRecordLayout lasRecordLayout(int format);

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
  std::size_t describedLength = 0;  ///< bytes of a record its format and the Extra Bytes descriptors account for
  LasCoordinateSystem coordinateSystem;
  std::vector<std::string> quirks;  ///< what the header did not hold as the specification says, read anyway

  bool hasGpsTime() const { return lasRecordLayout(this->format).gpsTime >= 0; }
  bool hasRgb() const { return lasRecordLayout(this->format).rgb >= 0; }
  bool hasNir() const { return lasRecordLayout(this->format).nir >= 0; }
  bool extended() const { return this->format >= 6; } ///< formats 6-10: 4-bit returns, 16-bit scan angle
};

/// The size of a point record of each format (the standard fields only).
std::size_t lasFormatSize(int format);


/// Reads the header, the variable-length records and (LAS 1.4) the extended ones of a LAS file of `fileSize` bytes.
/// False with `error` saying what is wrong: not a LAS file, LAZ, an unknown version or format, a record length below
/// the format's, the point records past the end of the file (truncated), an Extra Bytes record that does not fit the
/// records, a record that runs into the points or past the end.
bool readLasHeader(std::istream& in, std::uint64_t fileSize, LasHeader& header, std::string& error);

/// A LAS point's attributes (all but its position), one pointer per column: T* where a read writes them, const T*
/// where a write takes them. Null: not wanted (read), or absent (written as 0; one return of one).
template <bool Const>
struct LasAttributesT
{
  template <typename T>
  using Column = std::conditional_t<Const, const T*, T*>;

  Column<std::uint16_t> intensity = nullptr;
  Column<std::uint8_t> returnNumber = nullptr;
  Column<std::uint8_t> numberOfReturns = nullptr;
  Column<std::uint8_t> classification = nullptr; ///< formats 0-5: the low 5 bits (the class); 6-10: the whole byte
  Column<float> scanAngle = nullptr;             ///< degrees (formats 6-10: the stored value times 0.006)
  Column<std::uint8_t> userData = nullptr;
  Column<std::uint16_t> pointSourceId = nullptr;
  // The flags, 0 or 1 each: formats 0-5 keep synthetic, key-point and withheld beside the class (overlap is class 12
  // there), 6-10 in a byte of their own with overlap and the scanner channel (0-3).
  Column<std::uint8_t> withheld = nullptr;
  Column<std::uint8_t> synthetic = nullptr;
  Column<std::uint8_t> keyPoint = nullptr;
  Column<std::uint8_t> overlap = nullptr;
  Column<std::uint8_t> scanDirection = nullptr;  ///< the mirror's direction (1: positive, left to right)
  Column<std::uint8_t> edgeOfFlightLine = nullptr;
  Column<std::uint8_t> scannerChannel = nullptr; ///< formats 6-10 only
  Column<double> gpsTime = nullptr;
  Column<std::uint16_t> rgb = nullptr;           ///< 3 per point, as stored (0-65535)
  Column<std::uint16_t> nir = nullptr;
};

/// Which point formats hold an attribute.
enum class LasPresence
{
  Always,
  WithGpsTime,
  WithRgb,
  WithNir,
  Extended ///< formats 6-10
};
bool presentIn(LasPresence presence, int format);

/// The names of the attributes that other parts read (the normal estimation's lidar evidence, the text readers'
/// colours and intensity), as forEachLasAttribute gives them.
namespace lasname
{
constexpr const char* Intensity = "Intensity";
constexpr const char* NumberOfReturns = "NumberOfReturns";
constexpr const char* Classification = "Classification";
constexpr const char* ScanAngle = "ScanAngle";
constexpr const char* Rgb = "RGB";
}

/// Calls visit(name, components, presence, column) for each attribute of `a` (a LasAttributesT), in the order the
/// readers list them: the one table of their names (the readers' point arrays, the writers' fields) and formats.
template <typename Attributes, typename Visit>
void forEachLasAttribute(Attributes& a, Visit&& visit)
{
  visit(lasname::Intensity, 1, LasPresence::Always, a.intensity);
  visit("ReturnNumber", 1, LasPresence::Always, a.returnNumber);
  visit(lasname::NumberOfReturns, 1, LasPresence::Always, a.numberOfReturns);
  visit(lasname::Classification, 1, LasPresence::Always, a.classification);
  visit(lasname::ScanAngle, 1, LasPresence::Always, a.scanAngle);
  visit("UserData", 1, LasPresence::Always, a.userData);
  visit("PointSourceId", 1, LasPresence::Always, a.pointSourceId);
  visit("Withheld", 1, LasPresence::Always, a.withheld);
  visit("Synthetic", 1, LasPresence::Always, a.synthetic);
  visit("KeyPoint", 1, LasPresence::Always, a.keyPoint);
  visit("Overlap", 1, LasPresence::Always, a.overlap);
  visit("ScanDirection", 1, LasPresence::Always, a.scanDirection);
  visit("EdgeOfFlightLine", 1, LasPresence::Always, a.edgeOfFlightLine);
  visit("ScannerChannel", 1, LasPresence::Extended, a.scannerChannel);
  visit("GpsTime", 1, LasPresence::WithGpsTime, a.gpsTime);
  visit(lasname::Rgb, 3, LasPresence::WithRgb, a.rgb);
  visit("NIR", 1, LasPresence::WithNir, a.nir);
}

/// Where the points go: arrays of header.pointCount values (3 per point for xyz, rgb), null for what is not wanted
/// or not in the format.
struct LasColumns : LasAttributesT<false>
{
  double* xyz = nullptr;                  ///< X * scale + offset, and so on (double precision)
  std::vector<double*> extra;             ///< one per header.extra (its components per point), scaled and shifted
  bool skipWithheld = false;              ///< leave the withheld points out (the arrays then hold the others first)
};

/// What a read of the points found.
struct LasReadResult
{
  std::uint64_t written = 0;        ///< points written to the columns
  std::uint64_t withheld = 0;       ///< points flagged withheld (left out when columns.skipWithheld)
  std::vector<std::string> quirks;  ///< what the points did not hold as the specification says, read anyway
};

/// Decodes the point records (in blocks, so that the file is never held whole), then checks every point (the
/// withheld ones too) against the header's bounds: a point outside them by more than a scale step means an
/// inconsistent file, unless the bounds read as stored unscaled (the integers, a writer's slip: a quirk). False with
/// `error`.
bool readLasPoints(
  std::istream& in, const LasHeader& header, LasColumns& columns, LasReadResult& result, std::string& error);

} // namespace gls
