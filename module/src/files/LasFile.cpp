#include "gls/LasFile.h"

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

/// The Extra Bytes record's descriptors (192 bytes each) into header.extra, placed after the format's fields.
bool parseExtraBytes(const unsigned char* data, std::size_t length, LasHeader& h, std::string& error)
{
  std::size_t at = lasFormatSize(h.format);
  for (std::size_t d = 0; d + 192 <= length; d += 192)
  {
    const unsigned char* e = data + d;
    const int type = e[2], options = e[3];
    char name[33] = {};
    std::memcpy(name, e + 4, 32);
    const std::size_t size = type == 0 ? static_cast<std::size_t>(options) : extraSize(type);
    if (type > 10)
    {
      error = "an Extra Bytes descriptor ('" + std::string(name) + "') has the deprecated array type " +
        std::to_string(type) + ", which this reader does not decode";
      return false;
    }
    if (type != 0)
    {
      LasExtraBytes x;
      x.name = name;
      x.dataType = type;
      x.offset = at;
      x.scale = (options & 8) ? f64(e + 112) : 1.0;
      x.shift = (options & 16) ? f64(e + 136) : 0.0;
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
  return true;
}

} // namespace

std::size_t lasFormatSize(int format)
{
  static const std::size_t sizes[] = { 20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67 };
  return format >= 0 && format <= 10 ? sizes[format] : 0;
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
    error = "not a LAS file (it does not begin with 'LASF')";
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
  if (h.versionMinor >= 4 && h.pointCount == 0)
  {
    h.pointCount = littleEndian(b + 247, 8);
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

/// The variable-length records between the header and the points: the Extra Bytes descriptors into h.extra. False
/// with the error when a record runs into the points or its descriptors do not fit the point records.
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
    if (std::string(user) == "LASF_Spec" && u16(v + 18) == 4)
    {
      std::vector<unsigned char> data(length);
      if (!readBytes(in, at + 54, data.data(), length) || !parseExtraBytes(data.data(), length, h, error))
      {
        error = error.empty() ? "cannot read the Extra Bytes record" : error;
        return false;
      }
    }
    at += 54 + length;
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
  return readLasPreamble(in, fileSize, b, h, headerSize, error) && readLasFields(b, h, vlrCount, error) &&
    checkLasRecords(h, headerSize, fileSize, error) && readVariableLengthRecords(in, headerSize, vlrCount, h, error);
}

namespace
{

/// Point i's position (X * scale + offset in double precision) from its record p, into c.xyz when asked, and into
/// the running bounds of the points.
void readLasPosition(
  const unsigned char* p, std::uint64_t i, const LasHeader& h, LasColumns& c, double* low, double* high)
{
  for (int a = 0; a < 3; ++a)
  {
    const double v = i32(p + 4 * a) * h.scale[a] + h.offset[a];
    low[a] = i == 0 ? v : std::min(low[a], v);
    high[a] = i == 0 ? v : std::max(high[a], v);
    if (c.xyz)
    {
      c.xyz[3 * i + a] = v;
    }
  }
}

/// Point i's attributes from its record p into the columns asked for (formats 6-10: 4-bit returns, the whole
/// classification byte, a 16-bit scan angle).
void readLasAttributes(const unsigned char* p, std::uint64_t i, const LasHeader& h, LasColumns& c)
{
  const bool ext = h.extended();
  if (c.intensity)
  {
    c.intensity[i] = u16(p + 12);
  }
  const int returns = p[14];
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
    c.classification[i] = ext ? p[16] : static_cast<std::uint8_t>(p[15] & 31);
  }
  if (c.scanAngle)
  {
    c.scanAngle[i] = ext ? static_cast<float>(static_cast<std::int16_t>(u16(p + 18)) * 0.006)
                         : static_cast<float>(static_cast<std::int8_t>(p[16]));
  }
  if (c.userData)
  {
    c.userData[i] = p[17];
  }
  if (c.pointSourceId)
  {
    c.pointSourceId[i] = u16(p + (ext ? 20 : 18));
  }
  if (c.gpsTime && h.hasGpsTime())
  {
    c.gpsTime[i] = f64(p + (ext ? 22 : 20));
  }
  if (c.rgb && h.hasRgb())
  {
    const std::size_t at = ext ? 30 : (h.format == 2 ? 20 : 28);
    for (int a = 0; a < 3; ++a)
    {
      c.rgb[3 * i + a] = u16(p + at + 2 * a);
    }
  }
  if (c.nir && h.hasNir())
  {
    c.nir[i] = u16(p + 36);
  }
  for (std::size_t e = 0; e < h.extra.size() && e < c.extra.size(); ++e)
  {
    if (c.extra[e])
    {
      const LasExtraBytes& x = h.extra[e];
      c.extra[e][i] = extraValue(p + x.offset, x.dataType) * x.scale + x.shift;
    }
  }
}

/// The header's bounds against the points' (within a scale step and a relative 1e-9 of rounding); false with the
/// error when the points leave them.
bool checkLasBounds(const LasHeader& h, const double* low, const double* high, std::string& error)
{
  for (int a = 0; a < 3 && h.pointCount > 0; ++a)
  {
    const double slack = std::abs(h.scale[a]) + 1e-9 * (std::abs(h.min[a]) + std::abs(h.max[a]));
    if (low[a] < h.min[a] - slack || high[a] > h.max[a] + slack)
    {
      std::ostringstream msg;
      msg.precision(17);
      msg << "the points span [" << low[a] << ", " << high[a] << "] along " << "xyz"[a] << ", outside the header's ["
          << h.min[a] << ", " << h.max[a] << "]: an inconsistent file";
      error = msg.str();
      return false;
    }
  }
  return true;
}

} // namespace

bool readLasPoints(std::istream& in, const LasHeader& h, LasColumns& c, std::string& error)
{
  // Blocks of about 4 MiB (never more records than the file has).
  const std::size_t block = static_cast<std::size_t>(
    std::max<std::uint64_t>(1, std::min<std::uint64_t>(h.pointCount, (std::size_t(4) << 20) / h.recordLength)));
  std::vector<unsigned char> buffer(block * h.recordLength);
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
      readLasPosition(p, first + k, h, c, low, high);
      readLasAttributes(p, first + k, h, c);
    }
  }
  return checkLasBounds(h, low, high, error);
}

} // namespace gls
