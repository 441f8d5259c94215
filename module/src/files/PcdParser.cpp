#include "gls/PointTextParser.h"

#include <algorithm>
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

} // namespace

PointText parsePcd(const char* data, std::size_t size)
{
  const auto fail = [](const std::string& what) {
    PointText failed;
    failed.error = what;
    return failed;
  };
  // The header: lines up to and including DATA.
  std::vector<PcdField> fields;
  std::size_t width = 0, height = 1, points = 0, at = 0, line = 0;
  double viewpoint[3] = { 0, 0, 0 };
  bool placed = false; // a VIEWPOINT other than PCL's default (0 0 0 1 0 0 0)
  std::string encoding;
  bool havePoints = false;
  while (at < size && encoding.empty())
  {
    std::size_t end = at;
    while (end < size && data[end] != '\n')
    {
      ++end;
    }
    const std::string text(data + at, end - at);
    at = end + 1;
    ++line;
    const std::vector<std::string> w = words(text);
    if (w.empty() || w[0][0] == '#')
    {
      continue;
    }
    const std::string key = w[0];
    const auto here = [&](const std::string& what) { return "line " + std::to_string(line) + ": " + what; };
    if (key == "VERSION")
    {
      continue;
    }
    if (key == "FIELDS")
    {
      fields.assign(w.size() - 1, PcdField());
      for (std::size_t k = 1; k < w.size(); ++k)
      {
        fields[k - 1].name = w[k];
      }
    }
    else if (key == "SIZE" || key == "TYPE" || key == "COUNT")
    {
      if (w.size() != fields.size() + 1)
      {
        return fail(here(key + " gives " + std::to_string(w.size() - 1) + " values for " +
          std::to_string(fields.size()) + " FIELDS"));
      }
      for (std::size_t k = 1; k < w.size(); ++k)
      {
        PcdField& f = fields[k - 1];
        if (key == "TYPE")
        {
          f.type = w[k][0];
          if (w[k].size() != 1 || (f.type != 'F' && f.type != 'U' && f.type != 'I'))
          {
            return fail(here("TYPE '" + w[k] + "' (F, U or I expected)"));
          }
        }
        else
        {
          const long v = std::strtol(w[k].c_str(), nullptr, 10);
          if (key == "SIZE" && v != 1 && v != 2 && v != 4 && v != 8)
          {
            return fail(here("SIZE " + w[k] + " (1, 2, 4 or 8 expected)"));
          }
          if (key == "COUNT" && !(v >= 1 && v <= 100000))
          {
            return fail(here("COUNT " + w[k] + " (1 to 100000 expected)"));
          }
          (key == "SIZE" ? f.size : f.count) = static_cast<std::size_t>(v);
        }
      }
    }
    else if (key == "WIDTH" || key == "HEIGHT" || key == "POINTS")
    {
      const double v = w.size() == 2 ? std::strtod(w[1].c_str(), nullptr) : -1.0;
      if (!(v >= 0.0 && v <= 1e12) || v != std::floor(v))
      {
        return fail(here(key + " needs one count"));
      }
      (key == "WIDTH" ? width : key == "HEIGHT" ? height : points) = static_cast<std::size_t>(v);
      havePoints = havePoints || key == "POINTS";
    }
    else if (key == "VIEWPOINT")
    {
      if (w.size() != 8)
      {
        return fail(here("VIEWPOINT needs 7 numbers (tx ty tz qw qx qy qz)"));
      }
      double q[7];
      for (int a = 0; a < 7; ++a)
      {
        q[a] = std::strtod(w[1 + a].c_str(), nullptr);
      }
      std::copy(q, q + 3, viewpoint);
      placed = q[0] != 0.0 || q[1] != 0.0 || q[2] != 0.0 || q[3] != 1.0 || q[4] != 0.0 || q[5] != 0.0 || q[6] != 0.0;
    }
    else if (key == "DATA")
    {
      encoding = w.size() == 2 ? w[1] : "?";
      if (encoding != "ascii" && encoding != "binary" && encoding != "binary_compressed")
      {
        return fail(here("DATA '" + encoding + "' (ascii, binary or binary_compressed expected)"));
      }
    }
    else
    {
      return fail(here("unknown PCD header line '" + key + "'"));
    }
  }
  if (encoding.empty() || fields.empty())
  {
    return fail("not a PCD file: no FIELDS and DATA lines");
  }
  if (!havePoints)
  {
    points = width * height;
  }
  // Where each field is, and which the cloud uses.
  std::size_t record = 0, values = 0;
  int x = -1, y = -1, z = -1, nx = -1, ny = -1, nz = -1, intensity = -1, rgb = -1;
  for (std::size_t k = 0; k < fields.size(); ++k)
  {
    PcdField& f = fields[k];
    f.offset = encoding == "ascii" ? values : record;
    record += f.size * f.count;
    values += f.count;
    const int i = static_cast<int>(k);
    const std::string& n = f.name;
    int* role = n == "x" ? &x : n == "y" ? &y : n == "z" ? &z : n == "normal_x" ? &nx : n == "normal_y" ? &ny
      : n == "normal_z" ? &nz : n == "intensity" ? &intensity : (n == "rgb" || n == "rgba") ? &rgb : nullptr;
    if (role && f.count == 1)
    {
      *role = i;
    }
  }
  if (x < 0 || y < 0 || z < 0)
  {
    return fail("the PCD file has no x, y and z fields");
  }
  // At least 2 characters a value in text, a record a point in binary, and LZF expands at most about 132 times.
  const double held = static_cast<double>(size - std::min(at, size)) * (encoding == "binary_compressed" ? 140.0 : 1.0);
  if (static_cast<double>(points) * static_cast<double>(encoding == "ascii" ? 2 * values : record) > held)
  {
    return fail("the header announces " + std::to_string(points) +
      " points, more than the file holds (truncated, or a wrong POINTS)");
  }
  // The values of every point, field-major in one array of doubles (the first value of each field).
  std::vector<double> v(fields.size() * points, std::numeric_limits<double>::quiet_NaN());
  const auto put = [&](std::size_t field, std::size_t point, double value) { v[field * points + point] = value; };
  if (encoding == "ascii")
  {
    std::size_t point = 0;
    while (at < size && point < points)
    {
      std::size_t end = at;
      while (end < size && data[end] != '\n')
      {
        ++end;
      }
      const std::vector<std::string> w = words(std::string(data + at, end - at));
      at = end + 1;
      ++line;
      if (w.empty())
      {
        continue;
      }
      if (w.size() != values)
      {
        return fail("line " + std::to_string(line) + ": " + std::to_string(w.size()) + " values, " +
          std::to_string(values) + " expected");
      }
      for (std::size_t k = 0; k < fields.size(); ++k)
      {
        const std::string& s = w[fields[k].offset];
        char* stop = nullptr;
        double value = std::strtod(s.c_str(), &stop);
        if (stop == s.c_str())
        {
          return fail("line " + std::to_string(line) + ": not a number: '" + s + "'");
        }
        if (static_cast<int>(k) == rgb)
        {
          // Packed colours in text: PCL writes the float's bits as an integer (or the float itself).
          const std::uint32_t bits = value == std::floor(value) && value >= 0 && value < 4294967296.0
            ? static_cast<std::uint32_t>(value)
            : [&] { float f = static_cast<float>(value); std::uint32_t b; std::memcpy(&b, &f, 4); return b; }();
          value = static_cast<double>(bits);
        }
        put(k, point, value);
      }
      ++point;
    }
    if (point < points)
    {
      return fail("the file ends after " + std::to_string(point) + " of its " + std::to_string(points) +
        " points (truncated)");
    }
  }
  else
  {
    std::vector<unsigned char> unpacked;
    const unsigned char* bytes = reinterpret_cast<const unsigned char*>(data) + at;
    std::size_t available = size - std::min(at, size);
    const bool columns = encoding == "binary_compressed";
    if (columns)
    {
      if (available < 8)
      {
        return fail("binary_compressed data without its two sizes");
      }
      std::uint32_t packed = 0, plain = 0;
      for (int b = 3; b >= 0; --b)
      {
        packed = (packed << 8) | bytes[b];
        plain = (plain << 8) | bytes[4 + b];
      }
      if (plain != points * record || packed > available - 8)
      {
        return fail("binary_compressed sizes (" + std::to_string(packed) + " packed, " + std::to_string(plain) +
          " unpacked) do not match " + std::to_string(points) + " points of " + std::to_string(record) +
          " bytes in a file of " + std::to_string(size) + " bytes");
      }
      unpacked.resize(plain);
      if (!lzfDecompress(bytes + 8, packed, unpacked.data(), plain))
      {
        return fail("damaged binary_compressed (LZF) data");
      }
      bytes = unpacked.data();
      available = plain;
    }
    if (available < points * record)
    {
      return fail("the file holds " + std::to_string(available / std::max<std::size_t>(record, 1)) + " of its " +
        std::to_string(points) + " points (truncated)");
    }
    std::size_t columnStart = 0;
    for (std::size_t k = 0; k < fields.size(); ++k)
    {
      const PcdField& f = fields[k];
      for (std::size_t p = 0; p < points; ++p)
      {
        // binary: point-major records; binary_compressed: each field's values for every point, in turn.
        const unsigned char* at8 = columns ? bytes + columnStart + p * f.size * f.count : bytes + p * record + f.offset;
        put(k, p, binaryValue(at8, f));
      }
      columnStart += points * f.size * f.count;
    }
  }
  // The cloud.
  PointText out;
  out.points.resize(3 * points);
  for (std::size_t p = 0; p < points; ++p)
  {
    out.points[3 * p] = v[static_cast<std::size_t>(x) * points + p];
    out.points[3 * p + 1] = v[static_cast<std::size_t>(y) * points + p];
    out.points[3 * p + 2] = v[static_cast<std::size_t>(z) * points + p];
    if (placed)
    {
      out.viewpoints.insert(out.viewpoints.end(), viewpoint, viewpoint + 3);
    }
  }
  if (nx >= 0 && ny >= 0 && nz >= 0)
  {
    for (std::size_t p = 0; p < points; ++p)
    {
      for (int c : { nx, ny, nz })
      {
        out.normals.push_back(v[static_cast<std::size_t>(c) * points + p]);
      }
    }
  }
  if (intensity >= 0)
  {
    for (std::size_t p = 0; p < points; ++p)
    {
      out.intensity.push_back(static_cast<float>(v[static_cast<std::size_t>(intensity) * points + p]));
    }
  }
  if (rgb >= 0)
  {
    const PcdField& f = fields[static_cast<std::size_t>(rgb)];
    for (std::size_t p = 0; p < points; ++p)
    {
      // The packed 0x00RRGGBB in the field's bits (a float's, for PCL's F rgb).
      double value = v[static_cast<std::size_t>(rgb) * points + p];
      std::uint32_t bits = 0;
      if (f.type == 'F' && encoding != "ascii")
      {
        const float fv = static_cast<float>(value);
        std::memcpy(&bits, &fv, 4);
      }
      else
      {
        bits = static_cast<std::uint32_t>(value);
      }
      out.colors.push_back(static_cast<unsigned char>((bits >> 16) & 255));
      out.colors.push_back(static_cast<unsigned char>((bits >> 8) & 255));
      out.colors.push_back(static_cast<unsigned char>(bits & 255));
    }
  }
  std::ostringstream layout;
  layout << "PCD (" << encoding << "):";
  for (std::size_t k = 0; k < fields.size(); ++k)
  {
    const int i = static_cast<int>(k);
    layout << " " << fields[k].name;
    if (i != x && i != y && i != z && i != nx && i != ny && i != nz && i != intensity && i != rgb)
    {
      if (fields[k].count == 1)
      {
        PointTextColumn column;
        column.name = fields[k].name;
        column.values.assign(v.begin() + static_cast<std::ptrdiff_t>(k * points),
          v.begin() + static_cast<std::ptrdiff_t>((k + 1) * points));
        out.otherColumns.push_back(std::move(column));
      }
      else
      {
        layout << "[" << fields[k].count << " values: not read]";
      }
    }
  }
  if (placed)
  {
    layout << "; VIEWPOINT (" << viewpoint[0] << ", " << viewpoint[1] << ", " << viewpoint[2]
           << ") as every point's scanner position";
  }
  out.layout = layout.str();
  return out;
}

} // namespace gls
