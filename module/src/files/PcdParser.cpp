#include "gls/PointTextParser.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace gls
{
namespace
{

/// One field of a PCD header: its name, bytes per value, type (F, U, I) and count.
struct PcdField
{
  std::string name;
  std::size_t size = 4;
  char type = 'F';
  std::size_t count = 1;
  std::size_t offset = 0; ///< in a point record (binary) or in the values of a line (ascii: value index)
};

std::vector<std::string> words(const std::string& line)
{
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;)
  {
    out.push_back(w);
  }
  return out;
}

/// A value of the field at p (binary, little-endian as PCL writes on x86), as a double.
double binaryValue(const unsigned char* p, const PcdField& f)
{
  std::uint64_t bits = 0;
  for (std::size_t b = f.size; b-- > 0;)
  {
    bits = (bits << 8) | p[b];
  }
  if (f.type == 'F')
  {
    if (f.size == 4)
    {
      const std::uint32_t b32 = static_cast<std::uint32_t>(bits);
      float v;
      std::memcpy(&v, &b32, 4);
      return v;
    }
    double v;
    std::memcpy(&v, &bits, 8);
    return v;
  }
  if (f.type == 'I')
  {
    const int shift = static_cast<int>(64 - 8 * f.size);
    return static_cast<double>(static_cast<std::int64_t>(bits << shift) >> shift);
  }
  return static_cast<double>(bits);
}

/// LZF decompression (the format of PCD's binary_compressed): false when the data is damaged.
bool lzfDecompress(const unsigned char* in, std::size_t inSize, unsigned char* out, std::size_t outSize)
{
  std::size_t i = 0, o = 0;
  while (i < inSize)
  {
    const unsigned ctrl = in[i++];
    if (ctrl < 32)
    {
      const std::size_t run = ctrl + 1;
      if (i + run > inSize || o + run > outSize)
      {
        return false;
      }
      std::memcpy(out + o, in + i, run);
      i += run;
      o += run;
      continue;
    }
    std::size_t length = ctrl >> 5;
    if (length == 7)
    {
      if (i >= inSize)
      {
        return false;
      }
      length += in[i++];
    }
    if (i >= inSize)
    {
      return false;
    }
    const std::size_t back = ((ctrl & 31u) << 8) + in[i++] + 1;
    length += 2;
    if (back > o || o + length > outSize)
    {
      return false;
    }
    for (std::size_t k = 0; k < length; ++k, ++o)
    {
      out[o] = out[o - back]; // byte by byte: the copy may overlap itself
    }
  }
  return o == outSize;
}

/// A PCD header: its fields, counts, viewpoint and encoding, and where its data begin.
struct PcdHeader
{
  std::vector<PcdField> fields;
  std::size_t width = 0, height = 1, points = 0;
  bool havePoints = false;
  double viewpoint[3] = { 0, 0, 0 }; ///< the VIEWPOINT's translation: PCL's sensor origin (0 0 0 without one)
  std::string encoding;
  std::size_t dataStart = 0; ///< the byte after the DATA line
  std::size_t line = 0;      ///< the DATA line's number
};

/// Which field holds each value the cloud uses (-1: none; fields of one value only), and a point's size: bytes of a
/// binary record, values of an ascii line.
struct PcdRoles
{
  int x = -1, y = -1, z = -1, nx = -1, ny = -1, nz = -1, intensity = -1, rgb = -1;
  std::size_t record = 0, values = 0;

  bool used(int i) const
  {
    return i == x || i == y || i == z || i == nx || i == ny || i == nz || i == intensity || i == rgb;
  }
};

/// A SIZE, TYPE or COUNT line (w: its words) into the fields; "" or what is wrong.
std::string readFieldProperty(const std::vector<std::string>& w, std::vector<PcdField>& fields)
{
  const std::string& key = w[0];
  if (w.size() != fields.size() + 1)
  {
    return key + " gives " + std::to_string(w.size() - 1) + " values for " + std::to_string(fields.size()) +
      " FIELDS";
  }
  for (std::size_t k = 1; k < w.size(); ++k)
  {
    PcdField& f = fields[k - 1];
    if (key == "TYPE")
    {
      f.type = w[k][0];
      if (w[k].size() != 1 || (f.type != 'F' && f.type != 'U' && f.type != 'I'))
      {
        return "TYPE '" + w[k] + "' (F, U or I expected)";
      }
      continue;
    }
    const long v = std::strtol(w[k].c_str(), nullptr, 10);
    if (key == "SIZE" && v != 1 && v != 2 && v != 4 && v != 8)
    {
      return "SIZE " + w[k] + " (1, 2, 4 or 8 expected)";
    }
    if (key == "COUNT" && !(v >= 1 && v <= 100000))
    {
      return "COUNT " + w[k] + " (1 to 100000 expected)";
    }
    (key == "SIZE" ? f.size : f.count) = static_cast<std::size_t>(v);
  }
  return {};
}

/// One header line (w: its words, not empty, no comment) into h; "" or what is wrong.
std::string readHeaderLine(const std::vector<std::string>& w, PcdHeader& h)
{
  const std::string& key = w[0];
  if (key == "VERSION")
  {
    return {};
  }
  if (key == "FIELDS")
  {
    h.fields.assign(w.size() - 1, PcdField());
    for (std::size_t k = 1; k < w.size(); ++k)
    {
      h.fields[k - 1].name = w[k];
    }
    return {};
  }
  if (key == "SIZE" || key == "TYPE" || key == "COUNT")
  {
    return readFieldProperty(w, h.fields);
  }
  if (key == "WIDTH" || key == "HEIGHT" || key == "POINTS")
  {
    const double v = w.size() == 2 ? std::strtod(w[1].c_str(), nullptr) : -1.0;
    if (!(v >= 0.0 && v <= 1e12) || v != std::floor(v))
    {
      return key + " needs one count";
    }
    (key == "WIDTH" ? h.width : key == "HEIGHT" ? h.height : h.points) = static_cast<std::size_t>(v);
    h.havePoints = h.havePoints || key == "POINTS";
    return {};
  }
  if (key == "VIEWPOINT")
  {
    if (w.size() != 8)
    {
      return "VIEWPOINT needs 7 numbers (tx ty tz qw qx qy qz)";
    }
    double q[7];
    for (int a = 0; a < 7; ++a)
    {
      q[a] = std::strtod(w[1 + a].c_str(), nullptr);
    }
    std::copy(q, q + 3, h.viewpoint);
    return {};
  }
  if (key == "DATA")
  {
    h.encoding = w.size() == 2 ? w[1] : "?";
    if (h.encoding != "ascii" && h.encoding != "binary" && h.encoding != "binary_compressed")
    {
      return "DATA '" + h.encoding + "' (ascii, binary or binary_compressed expected)";
    }
    return {};
  }
  return "unknown PCD header line '" + key + "'";
}

/// The words of the line beginning at `at` (advanced past it).
std::vector<std::string> nextLineWords(const char* data, std::size_t size, std::size_t& at)
{
  std::size_t end = at;
  while (end < size && data[end] != '\n')
  {
    ++end;
  }
  std::vector<std::string> w = words(std::string(data + at, end - at));
  at = end + 1;
  return w;
}

/// The header: lines up to and including DATA; "" or what is wrong.
std::string readPcdHeader(const char* data, std::size_t size, PcdHeader& h)
{
  std::size_t at = 0;
  while (at < size && h.encoding.empty())
  {
    const std::vector<std::string> w = nextLineWords(data, size, at);
    ++h.line;
    if (w.empty() || w[0][0] == '#')
    {
      continue;
    }
    const std::string error = readHeaderLine(w, h);
    if (!error.empty())
    {
      return "line " + std::to_string(h.line) + ": " + error;
    }
  }
  h.dataStart = at;
  if (h.encoding.empty() || h.fields.empty())
  {
    return "not a PCD file: no FIELDS and DATA lines";
  }
  if (!h.havePoints)
  {
    h.points = h.width * h.height;
  }
  return {};
}

/// Where each field is (its offset), and which the cloud uses; "" or what is wrong.
std::string layOutFields(PcdHeader& h, PcdRoles& r)
{
  for (std::size_t k = 0; k < h.fields.size(); ++k)
  {
    PcdField& f = h.fields[k];
    f.offset = h.encoding == "ascii" ? r.values : r.record;
    r.record += f.size * f.count;
    r.values += f.count;
    // Names compared without case, as PCL (x, normal_x, rgb) and PDAL (X, Intensity) write them.
    std::string n = f.name;
    std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    int* role = n == "x" ? &r.x : n == "y" ? &r.y : n == "z" ? &r.z : n == "normal_x" ? &r.nx
      : n == "normal_y" ? &r.ny : n == "normal_z" ? &r.nz : n == "intensity" ? &r.intensity
      : (n == "rgb" || n == "rgba") ? &r.rgb : nullptr;
    if (role && *role < 0 && f.count == 1)
    {
      *role = static_cast<int>(k);
    }
  }
  if (r.x >= 0 && r.y >= 0 && r.z >= 0)
  {
    return "";
  }
  std::string fields;
  for (const PcdField& f : h.fields)
  {
    fields += (fields.empty() ? "" : " ") + f.name;
  }
  return "the PCD file has no x, y and z fields of one value each (its fields: " + fields +
    "): not a point cloud (an image's PCD?)";
}

/// The low 32 bits of the integer value (two's complement for negative values), as a packed colour reads them; 0 for
/// a value that is not finite.
std::uint32_t lowThirtyTwoBits(double integer)
{
  if (!std::isfinite(integer))
  {
    return 0;
  }
  constexpr double twoTo32 = 4294967296.0;
  const double low = std::fmod(integer, twoTo32); // exact for integers; in (-2^32, 2^32)
  return static_cast<std::uint32_t>(low < 0 ? low + twoTo32 : low);
}

/// The values of every point of ascii data, field-major in v (the first value of each field); "" or what is wrong.
std::string readAsciiValues(
  const char* data, std::size_t size, const PcdHeader& h, const PcdRoles& r, std::vector<double>& v)
{
  std::size_t at = h.dataStart, line = h.line, point = 0;
  while (at < size && point < h.points)
  {
    const std::vector<std::string> w = nextLineWords(data, size, at);
    ++line;
    if (w.empty())
    {
      continue;
    }
    if (w.size() != r.values)
    {
      return "line " + std::to_string(line) + ": " + std::to_string(w.size()) + " values, " +
        std::to_string(r.values) + " expected";
    }
    for (std::size_t k = 0; k < h.fields.size(); ++k)
    {
      const std::string& s = w[h.fields[k].offset];
      char* stop = nullptr;
      double value = std::strtod(s.c_str(), &stop);
      if (stop == s.c_str())
      {
        return "line " + std::to_string(line) + ": not a number: '" + s + "'";
      }
      if (static_cast<int>(k) == r.rgb)
      {
        // Packed colours in text: PCL writes the float's bits as an integer (or the float itself); an integer
        // field's value is its bits.
        const bool integral = std::isfinite(value) && value == std::floor(value);
        const std::uint32_t bits = integral && (h.fields[k].type != 'F' || (value >= 0 && value < 4294967296.0))
          ? lowThirtyTwoBits(value)
          : [&] { float f = static_cast<float>(value); std::uint32_t b; std::memcpy(&b, &f, 4); return b; }();
        value = static_cast<double>(bits);
      }
      v[k * h.points + point] = value;
    }
    ++point;
  }
  if (point < h.points)
  {
    return "the file ends after " + std::to_string(point) + " of its " + std::to_string(h.points) +
      " points (truncated)";
  }
  return {};
}

/// The values of every point of binary or binary_compressed data, field-major in v; "" or what is wrong.
std::string readBinaryValues(
  const char* data, std::size_t size, const PcdHeader& h, const PcdRoles& r, std::vector<double>& v)
{
  std::vector<unsigned char> unpacked;
  const unsigned char* bytes = reinterpret_cast<const unsigned char*>(data) + h.dataStart;
  std::size_t available = size - std::min(h.dataStart, size);
  const bool columns = h.encoding == "binary_compressed";
  if (columns)
  {
    if (available < 8)
    {
      return "binary_compressed data without its two sizes";
    }
    std::uint32_t packed = 0, plain = 0;
    for (int b = 3; b >= 0; --b)
    {
      packed = (packed << 8) | bytes[b];
      plain = (plain << 8) | bytes[4 + b];
    }
    if (plain != h.points * r.record || packed > available - 8)
    {
      return "binary_compressed sizes (" + std::to_string(packed) + " packed, " + std::to_string(plain) +
        " unpacked) do not match " + std::to_string(h.points) + " points of " + std::to_string(r.record) +
        " bytes in a file of " + std::to_string(size) + " bytes";
    }
    unpacked.resize(plain);
    if (!lzfDecompress(bytes + 8, packed, unpacked.data(), plain))
    {
      return "damaged binary_compressed (LZF) data";
    }
    bytes = unpacked.data();
    available = plain;
  }
  if (available < h.points * r.record)
  {
    return "the file holds " + std::to_string(available / std::max<std::size_t>(r.record, 1)) + " of its " +
      std::to_string(h.points) + " points (truncated)";
  }
  std::size_t columnStart = 0;
  for (std::size_t k = 0; k < h.fields.size(); ++k)
  {
    const PcdField& f = h.fields[k];
    for (std::size_t p = 0; p < h.points; ++p)
    {
      // binary: point-major records; binary_compressed: each field's values for every point, in turn.
      const unsigned char* at8 = columns ? bytes + columnStart + p * f.size * f.count : bytes + p * r.record + f.offset;
      v[k * h.points + p] = binaryValue(at8, f);
    }
    columnStart += h.points * f.size * f.count;
  }
  return {};
}

/// The packed 0x00RRGGBB colour of a value of the rgb field: a float's bits for PCL's F rgb in binary data, else the
/// integer's low 32 bits (two's complement: an rgba stored as I 4 is negative where alpha >= 128; a U 8 value may
/// exceed 32 bits). Text values arrive already as bits (readAsciiValues).
std::uint32_t packedColour(double value, const PcdField& f, const std::string& encoding)
{
  if (f.type == 'F' && encoding != "ascii")
  {
    const float fv = static_cast<float>(value);
    std::uint32_t bits = 0;
    std::memcpy(&bits, &fv, 4);
    return bits;
  }
  return lowThirtyTwoBits(value);
}

/// The cloud of the field-major values v: points, the viewpoint, normals, intensity, colours, the other fields.
PointText cloudOfValues(const PcdHeader& h, const PcdRoles& r, const std::vector<double>& v)
{
  const std::size_t points = h.points;
  const auto value = [&](int field, std::size_t p) { return v[static_cast<std::size_t>(field) * points + p]; };
  PointText out;
  out.points.resize(3 * points);
  for (std::size_t p = 0; p < points; ++p)
  {
    out.points[3 * p] = value(r.x, p);
    out.points[3 * p + 1] = value(r.y, p);
    out.points[3 * p + 2] = value(r.z, p);
  }
  out.hasSensor = true;
  std::copy(h.viewpoint, h.viewpoint + 3, out.sensor);
  for (std::size_t p = 0; r.nx >= 0 && r.ny >= 0 && r.nz >= 0 && p < points; ++p)
  {
    for (int c : { r.nx, r.ny, r.nz })
    {
      out.normals.push_back(value(c, p));
    }
  }
  for (std::size_t p = 0; r.intensity >= 0 && p < points; ++p)
  {
    out.intensity.push_back(static_cast<float>(value(r.intensity, p)));
  }
  for (std::size_t p = 0; r.rgb >= 0 && p < points; ++p)
  {
    const std::uint32_t bits = packedColour(value(r.rgb, p), h.fields[static_cast<std::size_t>(r.rgb)], h.encoding);
    out.colors.push_back(static_cast<unsigned char>((bits >> 16) & 255));
    out.colors.push_back(static_cast<unsigned char>((bits >> 8) & 255));
    out.colors.push_back(static_cast<unsigned char>(bits & 255));
  }
  std::ostringstream layout;
  layout << "PCD (" << h.encoding << "):";
  for (std::size_t k = 0; k < h.fields.size(); ++k)
  {
    layout << " " << h.fields[k].name;
    if (r.used(static_cast<int>(k)))
    {
      continue;
    }
    if (h.fields[k].count == 1)
    {
      PointTextColumn column;
      column.name = h.fields[k].name;
      column.values.assign(v.begin() + static_cast<std::ptrdiff_t>(k * points),
        v.begin() + static_cast<std::ptrdiff_t>((k + 1) * points));
      out.otherColumns.push_back(std::move(column));
    }
    else
    {
      layout << "[" << h.fields[k].count << " values: not read]";
    }
  }
  layout << "; the sensor at (" << h.viewpoint[0] << ", " << h.viewpoint[1] << ", " << h.viewpoint[2]
         << ") (VIEWPOINT)";
  if (h.width > 0 && h.height > 1 && h.width * h.height == h.points)
  {
    layout << "; organized " << h.width << " x " << h.height;
  }
  out.layout = layout.str();
  return out;
}

} // namespace

long long pcdAnnouncedPoints(const char* head, std::size_t size)
{
  PcdHeader h;
  return readPcdHeader(head, size, h).empty() ? static_cast<long long>(h.points) : -1;
}

PointText parsePcd(const char* data, std::size_t size)
{
  const auto fail = [](const std::string& what) {
    PointText failed;
    failed.error = what;
    return failed;
  };
  PcdHeader h;
  PcdRoles r;
  std::string error = readPcdHeader(data, size, h);
  if (error.empty())
  {
    error = layOutFields(h, r);
  }
  if (!error.empty())
  {
    return fail(error);
  }
  // At least 2 characters a value in text, a record a point in binary, and LZF expands at most about 132 times.
  const double held =
    static_cast<double>(size - std::min(h.dataStart, size)) * (h.encoding == "binary_compressed" ? 140.0 : 1.0);
  if (static_cast<double>(h.points) * static_cast<double>(h.encoding == "ascii" ? 2 * r.values : r.record) > held)
  {
    return fail("the header announces " + std::to_string(h.points) +
      " points, more than the file holds (truncated, or a wrong POINTS)");
  }
  std::vector<double> v(h.fields.size() * h.points, std::numeric_limits<double>::quiet_NaN());
  error = h.encoding == "ascii" ? readAsciiValues(data, size, h, r, v) : readBinaryValues(data, size, h, r, v);
  return error.empty() ? cloudOfValues(h, r, v) : fail(error);
}

} // namespace gls
