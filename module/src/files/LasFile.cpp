#include "gls/LasFile.h"

#include "gls/FileContent.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace gls
{
namespace
{

/// A little-endian unsigned integer of `bytes` bytes at p.
std::uint64_t littleEndian(const unsigned char* p, int bytes)
{
  std::uint64_t v = 0;
  for (int b = bytes - 1; b >= 0; --b)
  {
    v = (v << 8) | p[b];
  }
  return v;
}

std::uint16_t u16(const unsigned char* p)
{
  return static_cast<std::uint16_t>(littleEndian(p, 2));
}

std::uint32_t u32(const unsigned char* p)
{
  return static_cast<std::uint32_t>(littleEndian(p, 4));
}

std::int32_t i32(const unsigned char* p)
{
  return static_cast<std::int32_t>(u32(p));
}

double f64(const unsigned char* p)
{
  const std::uint64_t bits = littleEndian(p, 8);
  double v;
  std::memcpy(&v, &bits, sizeof(v));
  return v;
}

/// The value of an extra-bytes field of type t (1..10) at p, as a double.
double extraValue(const unsigned char* p, int t)
{
  switch (t)
  {
    case 1: return p[0];
    case 2: return static_cast<std::int8_t>(p[0]);
    case 3: return u16(p);
    case 4: return static_cast<std::int16_t>(u16(p));
    case 5: return u32(p);
    case 6: return i32(p);
    case 7: return static_cast<double>(littleEndian(p, 8));
    case 8: return static_cast<double>(static_cast<std::int64_t>(littleEndian(p, 8)));
    case 9:
    {
      const std::uint32_t bits = u32(p);
      float v;
      std::memcpy(&v, &bits, sizeof(v));
      return v;
    }
    default: return f64(p);
  }
}

std::size_t extraSize(int t)
{
  static const std::size_t sizes[] = { 0, 1, 1, 2, 2, 4, 4, 8, 8, 4, 8 };
  return t >= 1 && t <= 10 ? sizes[t] : 0;
}

bool readBytes(std::istream& in, std::uint64_t at, unsigned char* out, std::size_t n)
{
  in.clear();
  in.seekg(static_cast<std::streamoff>(at));
  in.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n));
  return static_cast<std::size_t>(in.gcount()) == n;
}

/// The Extra Bytes record's descriptors (192 bytes each) into header.extra, placed after the format's fields. The
/// deprecated array types (11-20: two values of type 1-10, 21-30: three) are read as components, with a quirk.
bool parseExtraBytes(const unsigned char* data, std::size_t length, LasHeader& h, std::string& error)
{
  std::size_t at = lasFormatSize(h.format);
  for (std::size_t d = 0; d + 192 <= length; d += 192)
  {
    const unsigned char* e = data + d;
    const int type = e[2], options = e[3];
    char name[33] = {};
    std::memcpy(name, e + 4, 32);
    if (type > 30)
    {
      error = "an Extra Bytes descriptor ('" + std::string(name) + "') has the data type " + std::to_string(type) +
        " (0 to 30 exist)";
      return false;
    }
    const int components = type == 0 ? 0 : (type - 1) / 10 + 1;
    const int base = type == 0 ? 0 : (type - 1) % 10 + 1;
    const std::size_t size = type == 0 ? static_cast<std::size_t>(options) : components * extraSize(base);
    if (type > 10)
    {
      h.quirks.push_back("the Extra Bytes field '" + std::string(name) + "' has the deprecated array type " +
        std::to_string(type) + " (LAS 1.4 R13; " + std::to_string(components) + " values of type " +
        std::to_string(base) + "): read as " + std::to_string(components) + " components");
    }
    if (type != 0)
    {
      LasExtraBytes x;
      x.name = name;
      x.dataType = base;
      x.components = components;
      x.offset = at;
      for (int c = 0; c < components; ++c)
      {
        x.scale[c] = (options & 8) ? f64(e + 112 + 8 * c) : 1.0;
        x.shift[c] = (options & 16) ? f64(e + 136 + 8 * c) : 0.0;
      }
      h.extra.push_back(x);
    }
    at += size;
  }
  if (at > h.recordLength)
  {
    std::ostringstream msg;
    msg << "the Extra Bytes record describes " << at << " bytes per point, but the point records have "
        << h.recordLength;
    error = msg.str();
    return false;
  }
  h.describedLength = at;
  return true;
}

} // namespace

std::size_t lasFormatSize(int format)
{
  static const std::size_t sizes[] = { 20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67 };
  return format >= 0 && format <= 10 ? sizes[format] : 0;
}

bool presentIn(LasPresence presence, int format)
{
  const LasRecordLayout l = lasRecordLayout(format);
  switch (presence)
  {
    case LasPresence::WithGpsTime: return l.gpsTime >= 0;
    case LasPresence::WithRgb: return l.rgb >= 0;
    case LasPresence::WithNir: return l.nir >= 0;
    case LasPresence::Extended: return l.extended;
    default: return true;
  }
}

LasRecordLayout lasRecordLayout(int format)
{
  LasRecordLayout l;
  if (format >= 6)
  {
    l.extended = true;
    l.flags = 15;
    l.classification = 16;
    l.userData = 17;
    l.scanAngle = 18;
    l.pointSourceId = 20;
    l.gpsTime = 22;
    l.rgb = format == 7 || format == 8 || format == 10 ? 30 : -1;
    l.nir = format == 8 || format == 10 ? 36 : -1;
    return l;
  }
  l.gpsTime = format == 1 || format >= 3 ? 20 : -1;
  l.rgb = format == 2 ? 20 : format == 3 || format == 5 ? 28 : -1;
  return l;
}

namespace
{

/// The header's first bytes: the signature, no compression, the version, a header size the version allows and the
/// file holds (the whole header is then in b). False with the error otherwise.
bool readLasPreamble(std::istream& in, std::uint64_t fileSize, unsigned char* b, LasHeader& h,
  std::size_t& headerSize, std::string& error)
{
  if (fileSize < 227 || !readBytes(in, 0, b, 227))
  {
    error = "too short for a LAS header (" + std::to_string(fileSize) + " bytes, at least 227 needed)";
    return false;
  }
  if (std::memcmp(b, "LASF", 4) != 0)
  {
    const std::string kind = binaryContentKind(reinterpret_cast<const char*>(b), 227);
    error = "not a LAS file (it does not begin with 'LASF'; by its content " + (kind.empty() ? "text" : kind) + ")";
    return false;
  }
  h.versionMajor = b[24];
  h.versionMinor = b[25];
  headerSize = u16(b + 94);
  if ((b[104] & 0xC0) != 0)
  {
    error = "compressed (LAZ) point records: decompress the file first (laszip -i in.laz -o out.las, "
            "pdal translate in.laz out.las, or CloudCompare), then read the .las";
    return false;
  }
  if (h.versionMajor != 1 || h.versionMinor > 4)
  {
    error = "LAS version " + std::to_string(h.versionMajor) + "." + std::to_string(h.versionMinor) +
      " (this reader takes 1.0 to 1.4)";
    return false;
  }
  const std::size_t needed = h.versionMinor >= 4 ? 375 : (h.versionMinor == 3 ? 235 : 227);
  if (headerSize < needed || fileSize < headerSize || (needed > 227 && !readBytes(in, 0, b, needed)))
  {
    std::ostringstream msg;
    msg << "the header size " << headerSize << " is below the " << needed << " bytes of a LAS 1."
        << h.versionMinor << " header, or past the end of the file (" << fileSize << " bytes)";
    error = msg.str();
    return false;
  }
  return true;
}

/// The header's fields (b: the whole header): the format, where the points are, how many, their scale, offset and
/// bounds. False with the error when the format is not one of 0 to 10.
bool readLasFields(const unsigned char* b, LasHeader& h, std::uint32_t& vlrCount, std::string& error)
{
  h.format = b[104];
  if (lasFormatSize(h.format) == 0)
  {
    error = "point data record format " + std::to_string(h.format) + " (this reader takes 0 to 10)";
    return false;
  }
  h.pointOffset = u32(b + 96);
  vlrCount = u32(b + 100);
  h.recordLength = u16(b + 105);
  h.pointCount = u32(b + 107);
  if (h.versionMinor >= 4)
  {
    // LAS 1.4 counts its points in 64 bits; the legacy field is 0 for formats 6-10 and beyond 2^32 points.
    const std::uint64_t legacy = h.pointCount, extended = littleEndian(b + 247, 8);
    h.pointCount = extended != 0 ? extended : legacy;
    if (extended == 0 && legacy != 0)
    {
      h.quirks.push_back("the LAS 1.4 header counts its " + std::to_string(legacy) +
        " points in the legacy field only (its 64-bit count is 0)");
    }
    else if (legacy != 0 && legacy != extended)
    {
      h.quirks.push_back("the LAS 1.4 header's legacy point count (" + std::to_string(legacy) +
        ") differs from its 64-bit count (" + std::to_string(extended) + "): the 64-bit count is read");
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    h.scale[a] = f64(b + 131 + 8 * a);
    h.offset[a] = f64(b + 155 + 8 * a);
    h.max[a] = f64(b + 179 + 16 * a);
    h.min[a] = f64(b + 187 + 16 * a);
  }
  return true;
}

/// The records as the file holds them: at least the format's size, usable scales and offsets, and every point
/// inside the file. False with the error otherwise.
bool checkLasRecords(const LasHeader& h, std::size_t headerSize, std::uint64_t fileSize, std::string& error)
{
  if (h.recordLength < lasFormatSize(h.format))
  {
    std::ostringstream msg;
    msg << "point records of " << h.recordLength << " bytes, below the " << lasFormatSize(h.format)
        << " of format " << h.format;
    error = msg.str();
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    if (!(h.scale[a] != 0.0) || !std::isfinite(h.scale[a]) || !std::isfinite(h.offset[a]))
    {
      error = "a scale factor of 0 or a non-finite scale or offset in the header";
      return false;
    }
  }
  // (Divided rather than multiplied: a 64-bit count from a damaged header must not wrap around.)
  if (h.pointOffset < headerSize || h.pointOffset > fileSize ||
    h.pointCount > (fileSize - h.pointOffset) / static_cast<std::uint64_t>(h.recordLength))
  {
    std::ostringstream msg;
    msg << "the header announces " << h.pointCount << " points of " << h.recordLength << " bytes from byte "
        << h.pointOffset << " (" << h.pointOffset + h.pointCount * h.recordLength << " bytes), but the file has "
        << fileSize << " bytes: truncated, or a wrong point count";
    error = msg.str();
    return false;
  }
  return true;
}

/// A text record's characters up to its first NUL (or all of them).
std::string recordText(const std::vector<unsigned char>& data)
{
  const auto end = std::find(data.begin(), data.end(), static_cast<unsigned char>(0));
  return std::string(data.begin(), end);
}

/// A coordinate-system record (user LASF_Projection) into h.coordinateSystem: WKT (2112) or the GeoTIFF keys
/// (34735-34737); the others (2111, a math transform) are not read.
void readProjectionRecord(int id, const std::vector<unsigned char>& data, LasHeader& h)
{
  LasCoordinateSystem& cs = h.coordinateSystem;
  if (id == 2112)
  {
    cs.wkt = recordText(data);
  }
  else if (id == 34735)
  {
    cs.geoKeys.resize(data.size() / 2);
    for (std::size_t k = 0; k < cs.geoKeys.size(); ++k)
    {
      cs.geoKeys[k] = u16(data.data() + 2 * k);
    }
  }
  else if (id == 34736)
  {
    cs.geoDoubles.resize(data.size() / 8);
    for (std::size_t k = 0; k < cs.geoDoubles.size(); ++k)
    {
      cs.geoDoubles[k] = f64(data.data() + 8 * k);
    }
  }
  else if (id == 34737)
  {
    cs.geoAscii = recordText(data);
  }
}

/// One record's body (the `length` bytes at `at`) where it matters: the Extra Bytes descriptors (LASF_Spec 4; `extra`:
/// a variable-length record, where the specification puts them) and the coordinate system. False with the error.
bool readRecordBody(std::istream& in, std::uint64_t at, std::uint64_t length, const std::string& user, int id,
  bool extra, LasHeader& h, std::string& error)
{
  const bool extraBytes = extra && user == "LASF_Spec" && id == 4;
  const bool projection = user == "LASF_Projection" && (id == 2112 || (id >= 34735 && id <= 34737));
  if (!extraBytes && !projection)
  {
    return true;
  }
  std::vector<unsigned char> data(static_cast<std::size_t>(length));
  if (!readBytes(in, at, data.data(), data.size()))
  {
    error = "cannot read the " + std::string(extraBytes ? "Extra Bytes" : "coordinate system") + " record";
    return false;
  }
  if (extraBytes)
  {
    return parseExtraBytes(data.data(), data.size(), h, error);
  }
  readProjectionRecord(id, data, h);
  return true;
}

/// The variable-length records between the header and the points: the Extra Bytes descriptors into h.extra, the
/// coordinate system. False with the error when a record runs into the points or its descriptors do not fit the
/// point records.
bool readVariableLengthRecords(
  std::istream& in, std::size_t headerSize, std::uint32_t vlrCount, LasHeader& h, std::string& error)
{
  std::uint64_t at = headerSize;
  for (std::uint32_t r = 0; r < vlrCount; ++r)
  {
    unsigned char v[54];
    if (at + 54 > h.pointOffset || !readBytes(in, at, v, 54))
    {
      error = "variable-length record " + std::to_string(r + 1) + " of " + std::to_string(vlrCount) +
        " runs into the point records";
      return false;
    }
    const std::size_t length = u16(v + 20);
    if (at + 54 + length > h.pointOffset)
    {
      error = "variable-length record " + std::to_string(r + 1) + " runs into the point records";
      return false;
    }
    char user[17] = {};
    std::memcpy(user, v + 2, 16);
    if (!readRecordBody(in, at + 54, length, user, u16(v + 18), true, h, error))
    {
      return false;
    }
    at += 54 + length;
  }
  return true;
}

/// LAS 1.4's extended variable-length records after the points (b: the header): the coordinate system where a
/// writer put it there. A record that lies outside the file is not read (a quirk: the points do not need it); false
/// with the error when an Extra Bytes or coordinate-system record cannot be read.
bool readExtendedRecords(std::istream& in, const unsigned char* b, std::uint64_t fileSize, LasHeader& h,
  std::string& error)
{
  if (h.versionMinor < 4)
  {
    return true;
  }
  std::uint64_t at = littleEndian(b + 235, 8);
  const std::uint32_t count = u32(b + 243);
  for (std::uint32_t r = 0; r < count; ++r)
  {
    unsigned char v[60];
    const std::uint64_t pointsEnd = h.pointOffset + h.pointCount * h.recordLength; // checkLasRecords: in the file
    const bool inFile = at >= pointsEnd && at <= fileSize && fileSize - at >= 60 && readBytes(in, at, v, 60);
    const std::uint64_t length = inFile ? littleEndian(v + 20, 8) : 0;
    if (!inFile || length > fileSize - at - 60)
    {
      h.quirks.push_back("extended variable-length record " + std::to_string(r + 1) + " of " +
        std::to_string(count) + " (from byte " + std::to_string(at) + ") lies outside the file: not read");
      return true;
    }
    char user[17] = {};
    std::memcpy(user, v + 2, 16);
    if (!readRecordBody(in, at + 60, length, user, u16(v + 18), false, h, error))
    {
      return false;
    }
    at += 60 + length;
  }
  return true;
}

} // namespace

bool readLasHeader(std::istream& in, std::uint64_t fileSize, LasHeader& h, std::string& error)
{
  h = LasHeader();
  unsigned char b[375] = {};
  std::size_t headerSize = 0;
  std::uint32_t vlrCount = 0;
  if (!readLasPreamble(in, fileSize, b, h, headerSize, error) || !readLasFields(b, h, vlrCount, error) ||
    !checkLasRecords(h, headerSize, fileSize, error))
  {
    return false;
  }
  h.describedLength = lasFormatSize(h.format); // until an Extra Bytes record describes more
  if (!readVariableLengthRecords(in, headerSize, vlrCount, h, error) || !readExtendedRecords(in, b, fileSize, h, error))
  {
    return false;
  }
  if (h.recordLength > h.describedLength)
  {
    h.quirks.push_back("its point records hold " + std::to_string(h.recordLength - h.describedLength) +
      " bytes each beyond the " + std::to_string(h.describedLength) + " that format " + std::to_string(h.format) +
      (h.extra.empty() ? "" : " and its Extra Bytes record") + " describe: not read");
  }
  return true;
}

namespace
{

/// Point i's position (X * scale + offset in double precision) from its record p into c.xyz when asked.
void readLasPosition(const unsigned char* p, std::uint64_t i, const LasHeader& h, LasColumns& c)
{
  for (int a = 0; a < 3 && c.xyz; ++a)
  {
    c.xyz[3 * i + a] = i32(p + 4 * a) * h.scale[a] + h.offset[a];
  }
}

/// Whether record p is flagged withheld.
bool isWithheld(const unsigned char* p, const LasHeader& h)
{
  return h.extended() ? (p[15] & 4) != 0 : (p[15] & 128) != 0;
}

/// Record p's flags into the columns asked for (point i): formats 0-5 keep synthetic, key-point and withheld in the
/// classification byte's high bits and the scan direction and edge of flight line in the returns byte's, overlap as
/// class 12; formats 6-10 give them a byte of their own with overlap and the scanner channel.
void readLasFlags(const unsigned char* p, std::uint64_t i, const LasHeader& h, LasColumns& c)
{
  const bool ext = h.extended();
  const int flags = ext ? p[15] : p[15] >> 5; // synthetic, key-point, withheld in bits 0-2 either way
  const int edges = ext ? p[15] >> 6 : p[14] >> 6; // scan direction, edge of flight line
  const auto put = [i](std::uint8_t* column, int value) {
    if (column)
    {
      column[i] = static_cast<std::uint8_t>(value);
    }
  };
  put(c.synthetic, flags & 1);
  put(c.keyPoint, (flags >> 1) & 1);
  put(c.withheld, (flags >> 2) & 1);
  put(c.overlap, ext ? (p[15] >> 3) & 1 : (p[15] & 31) == 12 ? 1 : 0);
  put(c.scanDirection, edges & 1);
  put(c.edgeOfFlightLine, (edges >> 1) & 1);
  if (ext)
  {
    put(c.scannerChannel, (p[15] >> 4) & 3);
  }
}

/// Point i's attributes from its record p into the columns asked for, where `l` (its format's) places them.
void readLasAttributes(const unsigned char* p, std::uint64_t i, const LasHeader& h, const LasRecordLayout& l,
  LasColumns& c)
{
  const bool ext = l.extended;
  readLasFlags(p, i, h, c);
  if (c.intensity)
  {
    c.intensity[i] = u16(p + 12);
  }
  const int returns = p[l.returns];
  if (c.returnNumber)
  {
    c.returnNumber[i] = static_cast<std::uint8_t>(ext ? returns & 15 : returns & 7);
  }
  if (c.numberOfReturns)
  {
    c.numberOfReturns[i] = static_cast<std::uint8_t>(ext ? returns >> 4 : (returns >> 3) & 7);
  }
  if (c.classification)
  {
    c.classification[i] = ext ? p[l.classification] : static_cast<std::uint8_t>(p[l.classification] & 31);
  }
  if (c.scanAngle)
  {
    c.scanAngle[i] = ext ? static_cast<float>(static_cast<std::int16_t>(u16(p + l.scanAngle)) * 0.006)
                         : static_cast<float>(static_cast<std::int8_t>(p[l.scanAngle]));
  }
  if (c.userData)
  {
    c.userData[i] = p[l.userData];
  }
  if (c.pointSourceId)
  {
    c.pointSourceId[i] = u16(p + l.pointSourceId);
  }
  if (c.gpsTime && l.gpsTime >= 0)
  {
    c.gpsTime[i] = f64(p + l.gpsTime);
  }
  if (c.rgb && l.rgb >= 0)
  {
    for (int a = 0; a < 3; ++a)
    {
      c.rgb[3 * i + a] = u16(p + l.rgb + 2 * a);
    }
  }
  if (c.nir && l.nir >= 0)
  {
    c.nir[i] = u16(p + l.nir);
  }
  for (std::size_t e = 0; e < h.extra.size() && e < c.extra.size(); ++e)
  {
    if (c.extra[e])
    {
      const LasExtraBytes& x = h.extra[e];
      const std::size_t size = extraSize(x.dataType);
      for (int k = 0; k < x.components; ++k)
      {
        c.extra[e][x.components * i + k] = extraValue(p + x.offset + k * size, x.dataType) * x.scale[k] + x.shift[k];
      }
    }
  }
}

/// Whether every point lies in [low, high] (per axis) within a scale step and a relative 1e-9 of rounding.
bool pointsWithin(const LasHeader& h, const double* low, const double* high, const double* min, const double* max)
{
  for (int a = 0; a < 3; ++a)
  {
    const double slack = std::abs(h.scale[a]) + 1e-9 * (std::abs(min[a]) + std::abs(max[a]));
    if (low[a] < min[a] - slack || high[a] > max[a] + slack)
    {
      return false;
    }
  }
  return true;
}

/// The header's bounds against the points' (low, high); false with the error when the points leave them, unless the
/// bounds hold them once read as unscaled integers (a quirk then).
bool checkLasBounds(const LasHeader& h, const double* low, const double* high, LasReadResult& result,
  std::string& error)
{
  if (h.pointCount == 0 || pointsWithin(h, low, high, h.min, h.max))
  {
    return true;
  }
  double min[3], max[3];
  for (int a = 0; a < 3; ++a)
  {
    min[a] = h.min[a] * h.scale[a] + h.offset[a];
    max[a] = h.max[a] * h.scale[a] + h.offset[a];
  }
  if (pointsWithin(h, low, high, min, max))
  {
    result.quirks.push_back("the header's bounds are stored unscaled (the integers, not the coordinates): read as "
                            "such");
    return true;
  }
  for (int a = 0; a < 3; ++a)
  {
    const double slack = std::abs(h.scale[a]) + 1e-9 * (std::abs(h.min[a]) + std::abs(h.max[a]));
    if (low[a] < h.min[a] - slack || high[a] > h.max[a] + slack)
    {
      std::ostringstream msg;
      msg.precision(17);
      msg << "the points span [" << low[a] << ", " << high[a] << "] along " << "xyz"[a] << ", outside the header's ["
          << h.min[a] << ", " << h.max[a] << "]: an inconsistent file";
      error = msg.str();
      break;
    }
  }
  return false;
}

} // namespace

bool readLasPoints(std::istream& in, const LasHeader& h, LasColumns& c, LasReadResult& result, std::string& error)
{
  result = LasReadResult();
  // Blocks of about 4 MiB (never more records than the file has).
  const std::size_t block = static_cast<std::size_t>(
    std::max<std::uint64_t>(1, std::min<std::uint64_t>(h.pointCount, (std::size_t(4) << 20) / h.recordLength)));
  std::vector<unsigned char> buffer(block * h.recordLength);
  const LasRecordLayout layout = lasRecordLayout(h.format);
  double low[3], high[3];
  for (std::uint64_t first = 0; first < h.pointCount; first += block)
  {
    const std::size_t count = static_cast<std::size_t>(std::min<std::uint64_t>(block, h.pointCount - first));
    if (!readBytes(in, h.pointOffset + first * h.recordLength, buffer.data(), count * h.recordLength))
    {
      error = "cannot read the point records from point " + std::to_string(first);
      return false;
    }
    for (std::size_t k = 0; k < count; ++k)
    {
      const unsigned char* p = buffer.data() + k * h.recordLength;
      for (int a = 0; a < 3; ++a) // the bounds of every point, a withheld one too
      {
        const double v = i32(p + 4 * a) * h.scale[a] + h.offset[a];
        low[a] = first + k == 0 ? v : std::min(low[a], v);
        high[a] = first + k == 0 ? v : std::max(high[a], v);
      }
      const bool withheld = isWithheld(p, h);
      result.withheld += withheld ? 1 : 0;
      if (withheld && c.skipWithheld)
      {
        continue;
      }
      readLasPosition(p, result.written, h, c);
      readLasAttributes(p, result.written, h, layout, c);
      ++result.written;
    }
  }
  return checkLasBounds(h, low, high, result, error);
}

} // namespace gls
