#include "gls/LasWriter.h"

#include "gls/Numeric.h"

#include "LittleEndian.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace gls
{
namespace
{

/// A byte buffer of little-endian values and fixed-width text fields.
class Bytes
{
public:
  template <typename T>
  void put(T v)
  {
    appendLittleEndian(this->data, v);
  }
  /// `text` in a field of `width` bytes, NUL-padded (cut when longer).
  void text(const std::string& text, std::size_t width)
  {
    std::string t = text.substr(0, width);
    t.resize(width, '\0');
    this->data += t;
  }
  void zeros(std::size_t n) { this->data.append(n, '\0'); }
  std::string data;
};

constexpr std::size_t kHeaderSize = 375;
constexpr std::size_t kRecordHeaderSize = 54;
constexpr double kLargestInteger = 2147483647.0;

/// The Extra Bytes fields of the sources: one float32 each per component.
struct ExtraField
{
  std::string name, description;
  const LasExtraSource* source;
  int component;
};

std::vector<ExtraField> extraFields(const LasWriteSource& s)
{
  std::vector<ExtraField> fields;
  for (const LasExtraSource& e : s.extra)
  {
    for (int c = 0; c < e.components; ++c)
    {
      std::string suffix;
      if (e.components == 3)
      {
        suffix = std::string("_") + "xyz"[c];
      }
      else if (e.components > 1)
      {
        suffix = "_" + std::to_string(c);
      }
      fields.push_back({ e.name.substr(0, 32 - suffix.size()) + suffix, e.description, &e, c });
    }
  }
  return fields;
}

/// A variable-length record: its 54-byte header and body.
void addRecord(Bytes& b, const std::string& user, std::uint16_t id, const std::string& description,
  const std::string& body)
{
  b.put<std::uint16_t>(0);
  b.text(user, 16);
  b.put<std::uint16_t>(id);
  b.put<std::uint16_t>(static_cast<std::uint16_t>(body.size()));
  b.text(description, 32);
  b.data += body;
}

/// The variable-length records: the Extra Bytes descriptors (float32, no scale or offset), the coordinate system.
Bytes records(const LasWriteSource& s, const std::vector<ExtraField>& fields, std::uint32_t& count)
{
  Bytes b;
  count = 0;
  if (!fields.empty())
  {
    Bytes d;
    for (const ExtraField& f : fields)
    {
      d.zeros(2);
      d.put<std::uint8_t>(9); // float
      d.put<std::uint8_t>(0); // no no_data, min, max, scale or offset
      d.text(f.name, 32);
      d.zeros(4 + 5 * 24);
      d.text(f.description, 32);
    }
    addRecord(b, "LASF_Spec", 4, "GLS values (float32)", d.data);
    ++count;
  }
  const LasCoordinateSystem& cs = s.coordinateSystem;
  if (!cs.wkt.empty())
  {
    addRecord(b, "LASF_Projection", 2112, "OGC coordinate system WKT", cs.wkt + std::string(1, '\0'));
    ++count;
  }
  if (!cs.geoKeys.empty())
  {
    Bytes keys, doubles;
    for (std::uint16_t k : cs.geoKeys)
    {
      keys.put<std::uint16_t>(k);
    }
    addRecord(b, "LASF_Projection", 34735, "GeoTIFF GeoKeyDirectoryTag", keys.data);
    ++count;
    if (!cs.geoDoubles.empty())
    {
      for (double d : cs.geoDoubles)
      {
        doubles.put<double>(d);
      }
      addRecord(b, "LASF_Projection", 34736, "GeoTIFF GeoDoubleParamsTag", doubles.data);
      ++count;
    }
    if (!cs.geoAscii.empty())
    {
      addRecord(b, "LASF_Projection", 34737, "GeoTIFF GeoAsciiParamsTag", cs.geoAscii + std::string(1, '\0'));
      ++count;
    }
  }
  return b;
}

/// The integers of point i's position; false when one does not fit 32 bits (`axis` says which).
bool integersOf(const LasWriteSource& s, std::size_t i, std::int32_t q[3], int& axis)
{
  for (int a = 0; a < 3; ++a)
  {
    const double v = std::round((s.xyz[3 * i + a] - s.offset[a]) / s.scale[a]);
    if (!(std::abs(v) <= kLargestInteger))
    {
      axis = a;
      return false;
    }
    q[a] = static_cast<std::int32_t>(v);
  }
  return true;
}

template <typename T>
T valueOr(const T* column, std::size_t i, T otherwise)
{
  return column ? column[i] : otherwise;
}

/// Point i's record (the standard fields as `l` places them, then the Extra Bytes fields) into p.
void encodeRecord(const LasWriteSource& s, std::size_t i, const std::int32_t q[3], const LasRecordLayout& l,
  const std::vector<ExtraField>& fields, Bytes& p)
{
  for (int a = 0; a < 3; ++a)
  {
    p.put<std::int32_t>(q[a]);
  }
  p.put<std::uint16_t>(valueOr<std::uint16_t>(s.intensity, i, 0));
  const int number = std::min<int>(15, valueOr<std::uint8_t>(s.returnNumber, i, 1));
  const int returns = std::min<int>(15, valueOr<std::uint8_t>(s.numberOfReturns, i, 1));
  p.put<std::uint8_t>(static_cast<std::uint8_t>(number | (returns << 4)));
  const auto bit = [i](const std::uint8_t* column, int shift) { return column && column[i] ? 1 << shift : 0; };
  const int channel = std::min<int>(3, valueOr<std::uint8_t>(s.scannerChannel, i, 0));
  p.put<std::uint8_t>(static_cast<std::uint8_t>(bit(s.synthetic, 0) | bit(s.keyPoint, 1) | bit(s.withheld, 2) |
    bit(s.overlap, 3) | (channel << 4) | bit(s.scanDirection, 6) | bit(s.edgeOfFlightLine, 7)));
  p.put<std::uint8_t>(valueOr<std::uint8_t>(s.classification, i, 0));
  p.put<std::uint8_t>(valueOr<std::uint8_t>(s.userData, i, 0));
  const double angle = std::round(static_cast<double>(valueOr<float>(s.scanAngle, i, 0.0f)) / 0.006);
  p.put<std::int16_t>(static_cast<std::int16_t>(std::isfinite(angle) ? std::clamp(angle, -30000.0, 30000.0) : 0.0));
  p.put<std::uint16_t>(valueOr<std::uint16_t>(s.pointSourceId, i, 0));
  p.put<double>(valueOr<double>(s.gpsTime, i, 0.0));
  if (l.rgb >= 0)
  {
    for (int c = 0; c < 3; ++c)
    {
      p.put<std::uint16_t>(s.rgb ? s.rgb[3 * i + c] : 0);
    }
  }
  if (l.nir >= 0)
  {
    p.put<std::uint16_t>(valueOr<std::uint16_t>(s.nir, i, 0));
  }
  for (const ExtraField& f : fields)
  {
    const LasExtraSource& e = *f.source;
    const std::size_t at = static_cast<std::size_t>(e.components) * i + static_cast<std::size_t>(f.component);
    p.put<float>(e.floats ? e.floats[at] : static_cast<float>(e.doubles[at]));
  }
}

} // namespace

bool lasIntegersHold(const double* xyz, std::size_t n, const double scale[3], const double offset[3])
{
  for (std::size_t i = 0; i < 3 * n; ++i)
  {
    const double* p = xyz + 3 * (i / 3);
    const int a = static_cast<int>(i % 3);
    if (isFinitePoint(p) && !(std::abs(std::round((p[a] - offset[a]) / scale[a])) <= kLargestInteger))
    {
      return false;
    }
  }
  return true;
}

bool chooseLasScaleAndOffset(const double* xyz, std::size_t n, double scale[3], double offset[3])
{
  double low[3] = { 0, 0, 0 }, high[3] = { 0, 0, 0 };
  bool any = false;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double* p = xyz + 3 * i;
    if (!isFinitePoint(p))
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      low[a] = any ? std::min(low[a], p[a]) : p[a];
      high[a] = any ? std::max(high[a], p[a]) : p[a];
    }
    any = true;
  }
  for (int a = 0; a < 3 && any; ++a)
  {
    offset[a] = low[a];
    const double extent = high[a] - low[a];
    double s = extent > 0.0 ? std::pow(10.0, std::ceil(std::log10(extent / kLargestInteger))) : 0.001;
    while (extent / s > kLargestInteger)
    {
      s *= 10.0;
    }
    scale[a] = s;
  }
  return any;
}

bool writeLas(std::ostream& out, const LasWriteSource& s, LasWriteResult& result, std::string& error)
{
  result = LasWriteResult();
  for (int a = 0; a < 3; ++a)
  {
    if (!(s.scale[a] > 0.0) || !std::isfinite(s.scale[a]) || !std::isfinite(s.offset[a]))
    {
      error = "a scale that is not positive and finite, or an offset that is not finite";
      return false;
    }
  }
  result.format = s.rgb ? (s.nir ? 8 : 7) : 6;
  const LasRecordLayout layout = lasRecordLayout(result.format);
  const std::vector<ExtraField> fields = extraFields(s);
  const std::size_t length = lasFormatSize(result.format) + 4 * fields.size();
  if (length > 65535 || fields.size() * 192 > 65535)
  {
    error = std::to_string(fields.size()) + " Extra Bytes fields: more than a LAS record holds";
    return false;
  }
  // A first pass: the integers fit, the bounds, the counts by return.
  double low[3] = { 0, 0, 0 }, high[3] = { 0, 0, 0 };
  std::uint64_t byReturn[15] = {};
  for (std::size_t i = 0; i < s.n; ++i)
  {
    if (!isFinitePoint(s.xyz + 3 * i))
    {
      ++result.leftOut;
      continue;
    }
    std::int32_t q[3];
    int axis = 0;
    if (!integersOf(s, i, q, axis))
    {
      std::ostringstream msg;
      msg.precision(17);
      msg << "point " << i << "'s " << "xyz"[axis] << " = " << s.xyz[3 * i + axis] << " is beyond the 32-bit "
          << "integers at the scale " << s.scale[axis] << " from the offset " << s.offset[axis];
      error = msg.str();
      return false;
    }
    for (int a = 0; a < 3; ++a)
    {
      const double v = q[a] * s.scale[a] + s.offset[a];
      low[a] = result.written == 0 ? v : std::min(low[a], v);
      high[a] = result.written == 0 ? v : std::max(high[a], v);
    }
    const int number = std::min<int>(15, valueOr<std::uint8_t>(s.returnNumber, i, 1));
    byReturn[std::max(number, 1) - 1] += 1;
    ++result.written;
  }
  std::uint32_t recordCount = 0;
  const Bytes vlrs = records(s, fields, recordCount);
  Bytes h;
  h.text("LASF", 4);
  h.put<std::uint16_t>(0);                                                          // file source id
  h.put<std::uint16_t>(static_cast<std::uint16_t>(s.coordinateSystem.wkt.empty() ? 0 : 16)); // WKT
  h.zeros(16);                                                                      // project id
  h.put<std::uint8_t>(1);
  h.put<std::uint8_t>(4);
  h.text("GLS", 32);
  h.text(s.software, 32);
  h.put<std::uint16_t>(1);
  h.put<std::uint16_t>(2026);
  h.put<std::uint16_t>(static_cast<std::uint16_t>(kHeaderSize));
  h.put<std::uint32_t>(static_cast<std::uint32_t>(kHeaderSize + vlrs.data.size()));
  h.put<std::uint32_t>(recordCount);
  h.put<std::uint8_t>(static_cast<std::uint8_t>(result.format));
  h.put<std::uint16_t>(static_cast<std::uint16_t>(length));
  h.zeros(4 + 5 * 4); // legacy counts: 0 for formats 6-10
  for (int a = 0; a < 3; ++a)
  {
    h.put<double>(s.scale[a]);
  }
  for (int a = 0; a < 3; ++a)
  {
    h.put<double>(s.offset[a]);
  }
  for (int a = 0; a < 3; ++a)
  {
    h.put<double>(high[a]);
    h.put<double>(low[a]);
  }
  h.put<std::uint64_t>(0); // no waveform records
  h.put<std::uint64_t>(0); // no extended records
  h.put<std::uint32_t>(0);
  h.put<std::uint64_t>(result.written);
  for (std::uint64_t r : byReturn)
  {
    h.put<std::uint64_t>(r);
  }
  out.write(h.data.data(), static_cast<std::streamsize>(h.data.size()));
  out.write(vlrs.data.data(), static_cast<std::streamsize>(vlrs.data.size()));
  // The records, in blocks of about 4 MiB.
  Bytes block;
  const std::size_t perBlock = std::max<std::size_t>(1, (std::size_t(4) << 20) / length);
  for (std::size_t i = 0; i < s.n && out; ++i)
  {
    std::int32_t q[3];
    int axis = 0;
    if (!isFinitePoint(s.xyz + 3 * i) || !integersOf(s, i, q, axis))
    {
      continue;
    }
    encodeRecord(s, i, q, layout, fields, block);
    if (block.data.size() >= perBlock * length)
    {
      out.write(block.data.data(), static_cast<std::streamsize>(block.data.size()));
      block.data.clear();
    }
  }
  out.write(block.data.data(), static_cast<std::streamsize>(block.data.size()));
  if (!out)
  {
    error = "the file could not be written (a full disk?)";
    return false;
  }
  return true;
}

} // namespace gls
