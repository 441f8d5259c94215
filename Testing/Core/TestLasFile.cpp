// LAS files (gls/LasFile.h) written byte by byte from the specification (ASPRS LAS 1.4 R15, tables 3-4 and 7-19) in
// every version and point format, read back; damaged files refused with what is wrong.
#include "gls/LasFile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

namespace
{

/// A little-endian byte writer.
struct Bytes
{
  std::string data;
  template <typename T>
  void put(T v)
  {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T)); // this machine is little-endian, as LAS is (checked below)
    data.append(b, sizeof(T));
  }
  void text(const std::string& s, std::size_t width)
  {
    std::string t = s.substr(0, width);
    t.resize(width, '\0');
    data += t;
  }
  void at(std::size_t offset, std::uint32_t v) { std::memcpy(&data[offset], &v, 4); }
};

/// One point's stored fields.
struct Point
{
  std::int32_t x, y, z;
  std::uint16_t intensity;
  int returnNumber, returns, classification;
  double scanAngle; ///< degrees
  std::uint8_t user;
  std::uint16_t source;
  double gps;
  std::uint16_t rgb[3];
  std::uint16_t nir;
  std::int16_t extra; ///< an Extra Bytes field "Amplitude" (i16, scale 0.5, offset 1) when asked
  int flags;          ///< synthetic (1), key-point (2), withheld (4), overlap (8; formats 6-10 only)
  int channel;        ///< the scanner channel (formats 6-10)
  int scanDirection, edge;
};

std::vector<Point> somePoints()
{
  std::vector<Point> p;
  for (int i = 0; i < 7; ++i)
  {
    p.push_back({ 1000 * i - 3000, 20 * i + 5, -7 * i, static_cast<std::uint16_t>(100 + i), 1 + i % 3, 3,
      2 + i % 5, -12.0 + 3.0 * i, static_cast<std::uint8_t>(i), static_cast<std::uint16_t>(40 + i),
      1.0e5 + 0.25 * i, { static_cast<std::uint16_t>(256 * i), 7, 65535 }, static_cast<std::uint16_t>(900 + i),
      static_cast<std::int16_t>(-3 + i), i % 8 == 0 ? 0 : (i * 3) % 16, i % 4, i % 2, (i / 2) % 2 });
  }
  return p;
}

const double kScale[3] = { 0.01, 0.01, 0.001 };
const double kOffset[3] = { 500000.0, 4000000.0, 100.0 };

/// A record of a LAS file's (extended) variable-length records.
struct Record
{
  std::string user;
  int id;
  std::string body;
};

/// What a test file holds beside the points, and the writers' slips it reproduces.
struct LasOptions
{
  int extraType = 0;                 ///< an Extra Bytes field "Amplitude" of this type (4: i16; 23: the deprecated
                                     ///< three u16); 0: none
  std::vector<Record> records;       ///< variable-length records after the Extra Bytes one
  std::vector<Record> extended;      ///< LAS 1.4's extended records, after the points
  bool unscaledBounds = false;       ///< the header's bounds written as the integers (simple1_3.las's slip)
  bool legacyCountOnly = false;      ///< LAS 1.4: the point count in the legacy field, the 64-bit one 0
  bool extendedOutside = false;      ///< LAS 1.4: the extended records' offset past the end of the file
};

/// The bytes of one u16 a component of type 23 (three), or the i16 of type 4.
std::size_t extraBytesOf(int type)
{
  return type == 0 ? 0 : type == 23 ? 6 : 2;
}

/// A LAS 1.minor file of the points in `format` with what `options` asks.
std::string lasFile(int minor, int format, const std::vector<Point>& points, const LasOptions& options = {})
{
  const std::size_t headerSize = minor >= 4 ? 375 : (minor == 3 ? 235 : 227);
  const std::size_t base = gls::lasFormatSize(format);
  const std::size_t recordLength = base + extraBytesOf(options.extraType);
  std::size_t vlrLength = options.extraType ? 54 + 192 : 0;
  for (const Record& r : options.records)
  {
    vlrLength += 54 + r.body.size();
  }
  const std::size_t pointsEnd = headerSize + vlrLength + points.size() * recordLength;
  Bytes b;
  b.text("LASF", 4);
  b.put<std::uint16_t>(0);
  b.put<std::uint16_t>(0);
  b.text("", 16);
  b.put<std::uint8_t>(1);
  b.put<std::uint8_t>(static_cast<std::uint8_t>(minor));
  b.text("GLS test", 32);
  b.text("TestLasFile", 32);
  b.put<std::uint16_t>(1);
  b.put<std::uint16_t>(2026);
  b.put<std::uint16_t>(static_cast<std::uint16_t>(headerSize));
  b.put<std::uint32_t>(static_cast<std::uint32_t>(headerSize + vlrLength));
  b.put<std::uint32_t>(static_cast<std::uint32_t>((options.extraType ? 1 : 0) + options.records.size()));
  b.put<std::uint8_t>(static_cast<std::uint8_t>(format));
  b.put<std::uint16_t>(static_cast<std::uint16_t>(recordLength));
  const bool legacy = minor < 4 || options.legacyCountOnly;
  b.put<std::uint32_t>(legacy ? static_cast<std::uint32_t>(points.size()) : 0);
  for (int r = 0; r < 5; ++r)
  {
    b.put<std::uint32_t>(0);
  }
  for (double s : kScale)
  {
    b.put<double>(s);
  }
  for (double o : kOffset)
  {
    b.put<double>(o);
  }
  for (int a = 0; a < 3; ++a)
  {
    double lo = 1e300, hi = -1e300;
    for (const Point& p : points)
    {
      const int v = a == 0 ? p.x : a == 1 ? p.y : p.z;
      const double c = options.unscaledBounds ? v : v * kScale[a] + kOffset[a];
      lo = std::min(lo, c);
      hi = std::max(hi, c);
    }
    b.put<double>(hi);
    b.put<double>(lo);
  }
  if (minor >= 3)
  {
    b.put<std::uint64_t>(0);
  }
  if (minor >= 4)
  {
    b.put<std::uint64_t>(options.extendedOutside ? pointsEnd + 1000000 : pointsEnd); // the first extended record
    b.put<std::uint32_t>(static_cast<std::uint32_t>(options.extended.size() + (options.extendedOutside ? 1 : 0)));
    b.put<std::uint64_t>(options.legacyCountOnly ? 0 : points.size());
    for (int r = 0; r < 15; ++r)
    {
      b.put<std::uint64_t>(0);
    }
  }
  EXPECT_EQ(b.data.size(), headerSize);
  if (options.extraType)
  {
    b.put<std::uint16_t>(0);
    b.text("LASF_Spec", 16);
    b.put<std::uint16_t>(4);
    b.put<std::uint16_t>(192);
    b.text("extra bytes", 32);
    b.put<std::uint16_t>(0);
    b.put<std::uint8_t>(static_cast<std::uint8_t>(options.extraType));
    b.put<std::uint8_t>(8 | 16);          // scale and offset given
    b.text("Amplitude", 32);
    b.text("", 4);
    b.text("", 24 * 3);                   // no_data, min, max
    for (double scale : { 0.5, 0.25, 2.0 })
    {
      b.put<double>(scale);
    }
    for (double offset : { 1.0, -1.0, 0.0 })
    {
      b.put<double>(offset);
    }
    b.text("an amplitude", 32);
  }
  for (const Record& r : options.records)
  {
    b.put<std::uint16_t>(0);
    b.text(r.user, 16);
    b.put<std::uint16_t>(static_cast<std::uint16_t>(r.id));
    b.put<std::uint16_t>(static_cast<std::uint16_t>(r.body.size()));
    b.text("a record", 32);
    b.data += r.body;
  }
  const bool ext = format >= 6;
  for (const Point& p : points)
  {
    const std::size_t start = b.data.size();
    b.put<std::int32_t>(p.x);
    b.put<std::int32_t>(p.y);
    b.put<std::int32_t>(p.z);
    b.put<std::uint16_t>(p.intensity);
    if (ext)
    {
      b.put<std::uint8_t>(static_cast<std::uint8_t>(p.returnNumber | (p.returns << 4)));
      b.put<std::uint8_t>(static_cast<std::uint8_t>(p.flags | (p.channel << 4) | (p.scanDirection << 6) | (p.edge << 7)));
      b.put<std::uint8_t>(static_cast<std::uint8_t>(p.classification));
      b.put<std::uint8_t>(p.user);
      b.put<std::int16_t>(static_cast<std::int16_t>(std::lround(p.scanAngle / 0.006)));
      b.put<std::uint16_t>(p.source);
      b.put<double>(p.gps);
    }
    else
    {
      b.put<std::uint8_t>(
        static_cast<std::uint8_t>(p.returnNumber | (p.returns << 3) | (p.scanDirection << 6) | (p.edge << 7)));
      b.put<std::uint8_t>(static_cast<std::uint8_t>(p.classification | ((p.flags & 7) << 5)));
      b.put<std::int8_t>(static_cast<std::int8_t>(p.scanAngle));
      b.put<std::uint8_t>(p.user);
      b.put<std::uint16_t>(p.source);
      if (format == 1 || format >= 3)
      {
        b.put<double>(p.gps);
      }
    }
    const bool rgb = format == 2 || format == 3 || format == 5 || format >= 7;
    if (rgb)
    {
      for (std::uint16_t c : p.rgb)
      {
        b.put<std::uint16_t>(c);
      }
    }
    if (format == 8 || format == 10)
    {
      b.put<std::uint16_t>(p.nir);
    }
    b.data.resize(start + base, '\0'); // wave packets: zeros
    for (std::size_t k = 0; k < extraBytesOf(options.extraType) / 2; ++k)
    {
      b.put<std::int16_t>(static_cast<std::int16_t>(p.extra + 10 * static_cast<int>(k)));
    }
  }
  EXPECT_EQ(b.data.size(), pointsEnd);
  for (const Record& r : options.extended)
  {
    b.put<std::uint16_t>(0);
    b.text(r.user, 16);
    b.put<std::uint16_t>(static_cast<std::uint16_t>(r.id));
    b.put<std::uint64_t>(r.body.size());
    b.text("an extended record", 32);
    b.data += r.body;
  }
  return b.data;
}

/// A file read from memory: the header, the points' columns, what the read found, or the error.
struct Decoded
{
  gls::LasHeader h;
  gls::LasReadResult read;
  std::string error;
  std::vector<double> xyz, gps, extra;
  std::vector<std::uint16_t> intensity, rgb, nir;
  std::vector<std::uint8_t> returnNumber, returns, classification, withheld, synthetic, keyPoint, overlap,
    scanDirection, edge, channel;
  std::vector<float> angle;
};

Decoded decode(const std::string& file, bool skipWithheld = false)
{
  Decoded d;
  std::istringstream in(file);
  if (!gls::readLasHeader(in, file.size(), d.h, d.error))
  {
    return d;
  }
  const std::size_t n = static_cast<std::size_t>(d.h.pointCount);
  d.xyz.assign(3 * n, 0.0);
  d.intensity.assign(n, 0);
  d.gps.assign(n, -1.0);
  d.rgb.assign(3 * n, 0);
  d.nir.assign(n, 0);
  d.angle.assign(n, 0.0f);
  d.extra.assign(3 * n, 0.0);
  for (auto* column : { &d.returnNumber, &d.returns, &d.classification, &d.withheld, &d.synthetic, &d.keyPoint,
         &d.overlap, &d.scanDirection, &d.edge, &d.channel })
  {
    column->assign(n, 255);
  }
  gls::LasColumns c;
  c.xyz = d.xyz.data();
  c.intensity = d.intensity.data();
  c.returnNumber = d.returnNumber.data();
  c.numberOfReturns = d.returns.data();
  c.classification = d.classification.data();
  c.scanAngle = d.angle.data();
  c.gpsTime = d.gps.data();
  c.rgb = d.rgb.data();
  c.nir = d.nir.data();
  c.withheld = d.withheld.data();
  c.synthetic = d.synthetic.data();
  c.keyPoint = d.keyPoint.data();
  c.overlap = d.overlap.data();
  c.scanDirection = d.scanDirection.data();
  c.edgeOfFlightLine = d.edge.data();
  c.scannerChannel = d.channel.data();
  c.extra.push_back(d.extra.data());
  c.skipWithheld = skipWithheld;
  gls::readLasPoints(in, d.h, c, d.read, d.error);
  return d;
}

} // namespace

TEST(LasFile, EveryVersionAndPointFormatReadsBack)
{
  const std::uint16_t one = 1;
  ASSERT_EQ(*reinterpret_cast<const unsigned char*>(&one), 1) << "the test's writer assumes a little-endian machine";
  const std::vector<Point> points = somePoints();
  for (int minor = 0; minor <= 4; ++minor)
  {
    for (int format = 0; format <= 10; ++format)
    {
      if ((minor < 3 && format > 3) || (minor == 3 && format > 5))
      {
        continue; // formats 4-5 came with LAS 1.3, 6-10 with 1.4
      }
      for (bool extraBytes : { false, true })
      {
        SCOPED_TRACE(testing::Message() << "LAS 1." << minor << ", format " << format << (extraBytes ? ", extra" : ""));
        LasOptions options;
        options.extraType = extraBytes ? 4 : 0;
        const Decoded d = decode(lasFile(minor, format, points, options));
        ASSERT_EQ(d.error, "");
        const gls::LasHeader& h = d.h;
        ASSERT_EQ(h.pointCount, points.size());
        ASSERT_EQ(d.read.written, points.size());
        EXPECT_TRUE(h.quirks.empty() && d.read.quirks.empty());
        ASSERT_EQ(h.extra.size(), extraBytes ? 1u : 0u);
        const bool ext = format >= 6;
        std::uint64_t withheld = 0;
        for (std::size_t i = 0; i < points.size(); ++i)
        {
          const Point& p = points[i];
          EXPECT_EQ(d.xyz[3 * i], p.x * kScale[0] + kOffset[0]);
          EXPECT_EQ(d.xyz[3 * i + 1], p.y * kScale[1] + kOffset[1]);
          EXPECT_EQ(d.xyz[3 * i + 2], p.z * kScale[2] + kOffset[2]);
          EXPECT_EQ(d.intensity[i], p.intensity);
          EXPECT_EQ(d.returnNumber[i], p.returnNumber);
          EXPECT_EQ(d.returns[i], p.returns);
          EXPECT_EQ(d.classification[i], p.classification); // without the flags
          EXPECT_NEAR(d.angle[i], p.scanAngle, 0.004);
          EXPECT_EQ(d.gps[i], h.hasGpsTime() ? p.gps : -1.0);
          for (int a = 0; a < 3; ++a)
          {
            EXPECT_EQ(d.rgb[3 * i + a], h.hasRgb() ? p.rgb[a] : 0);
          }
          EXPECT_EQ(d.nir[i], h.hasNir() ? p.nir : 0);
          // The flags: formats 0-5 keep three beside the class (overlap is class 12 there, none here), 6-10 four
          // and the scanner channel.
          EXPECT_EQ(d.synthetic[i], p.flags & 1);
          EXPECT_EQ(d.keyPoint[i], (p.flags >> 1) & 1);
          EXPECT_EQ(d.withheld[i], (p.flags >> 2) & 1);
          EXPECT_EQ(d.overlap[i], ext ? (p.flags >> 3) & 1 : 0);
          EXPECT_EQ(d.scanDirection[i], p.scanDirection);
          EXPECT_EQ(d.edge[i], p.edge);
          EXPECT_EQ(d.channel[i], ext ? p.channel : 255); // not written for formats 0-5
          withheld += (p.flags >> 2) & 1;
          if (extraBytes)
          {
            EXPECT_EQ(h.extra[0].name, "Amplitude");
            EXPECT_EQ(h.extra[0].components, 1);
            EXPECT_EQ(d.extra[i], 0.5 * p.extra + 1.0);
          }
        }
        EXPECT_EQ(d.read.withheld, withheld);
        EXPECT_GT(withheld, 0u);
      }
    }
  }
}

TEST(LasFile, WithheldPointsAreLeftOutWhenAsked)
{
  const std::vector<Point> points = somePoints();
  for (const int format : { 1, 6 })
  {
    SCOPED_TRACE(format);
    const Decoded d = decode(lasFile(4, format, points), true);
    ASSERT_EQ(d.error, "");
    std::size_t k = 0;
    for (const Point& p : points)
    {
      if ((p.flags >> 2) & 1)
      {
        continue;
      }
      EXPECT_EQ(d.xyz[3 * k], p.x * kScale[0] + kOffset[0]);
      EXPECT_EQ(d.intensity[k], p.intensity);
      EXPECT_EQ(d.withheld[k], 0);
      ++k;
    }
    EXPECT_EQ(d.read.written, k);
    EXPECT_EQ(d.read.withheld, points.size() - k);
    EXPECT_GT(d.read.withheld, 0u);
  }
}

TEST(LasFile, TheCoordinateSystemComesFromTheRecordsOrTheExtendedOnes)
{
  const std::vector<Point> points = somePoints();
  const std::string wkt = "PROJCS[\"NAD83 / UTM zone 10N\",GEOGCS[\"NAD83\"],UNIT[\"metre\",1]]";
  // GeoTIFF keys: a header (version 1, revision 1.0, 2 keys) and two keys; a double and an ascii parameter.
  const std::vector<std::uint16_t> keys = { 1, 1, 0, 2, 1024, 0, 1, 1, 3072, 0, 1, 26910 };
  std::string keyBytes(reinterpret_cast<const char*>(keys.data()), 2 * keys.size());
  const double parameter = 6378137.0;
  std::string doubleBytes(reinterpret_cast<const char*>(&parameter), 8);
  LasOptions both;
  both.records = { { "LASF_Projection", 2112, wkt + std::string(1, '\0') },
    { "LASF_Projection", 34735, keyBytes }, { "LASF_Projection", 34736, doubleBytes },
    { "LASF_Projection", 34737, "NAD83 / UTM zone 10N|NAD83|" + std::string(1, '\0') },
    { "someone", 7, "not read" } };
  const Decoded d = decode(lasFile(4, 6, points, both));
  ASSERT_EQ(d.error, "");
  EXPECT_EQ(d.h.coordinateSystem.wkt, wkt);
  EXPECT_EQ(d.h.coordinateSystem.geoKeys, keys);
  EXPECT_EQ(d.h.coordinateSystem.geoDoubles, std::vector<double>{ parameter });
  EXPECT_EQ(d.h.coordinateSystem.geoAscii, "NAD83 / UTM zone 10N|NAD83|");
  // LAS 1.4 may hold it in an extended record, after the points.
  LasOptions extended;
  extended.extended = { { "LASF_Projection", 2112, wkt } };
  const Decoded e = decode(lasFile(4, 7, points, extended));
  ASSERT_EQ(e.error, "");
  EXPECT_EQ(e.h.coordinateSystem.wkt, wkt);
  EXPECT_TRUE(e.h.coordinateSystem.geoKeys.empty());
  EXPECT_TRUE(e.h.quirks.empty());
  EXPECT_TRUE(decode(lasFile(2, 3, points)).h.coordinateSystem.empty());
}

TEST(LasFile, WritersQuirksAreReadWithANote)
{
  const std::vector<Point> points = somePoints();
  // Reads a file with a quirk: no error, every point, and a note holding `words`.
  const auto readWithQuirk = [&points](const std::string& file, const std::string& words) {
    Decoded d = decode(file);
    EXPECT_EQ(d.error, "");
    EXPECT_EQ(d.read.written, points.size());
    std::string all;
    for (const auto* quirks : { &d.h.quirks, &d.read.quirks })
    {
      for (const auto& q : *quirks)
      {
        all += q + "; ";
      }
    }
    EXPECT_NE(all.find(words), std::string::npos) << "no '" << words << "' in: " << all;
    return d;
  };
  // The deprecated array type 23 (three u16; laspy's extrabytes.las): three components, each its own scale and
  // offset.
  LasOptions deprecated;
  deprecated.extraType = 23;
  const Decoded a = readWithQuirk(lasFile(4, 3, points, deprecated), "deprecated array type 23");
  ASSERT_EQ(a.h.extra.size(), 1u);
  EXPECT_EQ(a.h.extra[0].components, 3);
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const std::uint16_t v = static_cast<std::uint16_t>(points[i].extra);
    EXPECT_EQ(a.extra[3 * i], 0.5 * v + 1.0);
    EXPECT_EQ(a.extra[3 * i + 1], 0.25 * static_cast<std::uint16_t>(points[i].extra + 10) - 1.0);
    EXPECT_EQ(a.extra[3 * i + 2], 2.0 * static_cast<std::uint16_t>(points[i].extra + 20));
  }
  // Bounds stored as the integers (simple1_3.las).
  LasOptions unscaled;
  unscaled.unscaledBounds = true;
  readWithQuirk(lasFile(3, 1, points, unscaled), "bounds are stored unscaled");
  // A LAS 1.4 count in the legacy field only.
  LasOptions legacy;
  legacy.legacyCountOnly = true;
  EXPECT_EQ(readWithQuirk(lasFile(4, 1, points, legacy), "legacy field only").h.pointCount, points.size());
  // Records longer than their format with no Extra Bytes record (laspy's unregistered_extra_bytes.las): 4 bytes each
  // not read.
  std::string padded = lasFile(4, 6, points);
  {
    // Each record 4 bytes longer: the header's record length and the points rewritten with padding.
    const std::size_t start = 375, length = gls::lasFormatSize(6);
    std::string body;
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      body += padded.substr(start + i * length, length) + std::string(4, '\x7f');
    }
    padded = padded.substr(0, start) + body;
    padded[105] = static_cast<char>(length + 4);
    padded.replace(235, 8, std::string(8, '\0')); // no extended records
  }
  const Decoded p = readWithQuirk(padded, "hold 4 bytes each beyond the 30 that format 6 describe");
  EXPECT_EQ(p.xyz[3], points[1].x * kScale[0] + kOffset[0]);
  // Extended records said to lie past the end of the file: not read, the points are.
  LasOptions outside;
  outside.extendedOutside = true;
  readWithQuirk(lasFile(4, 6, points, outside), "lies outside the file");
}

TEST(LasFile, DamagedFilesAreRefusedWithWhatIsWrong)
{
  const std::vector<Point> points = somePoints();
  const std::string good = lasFile(2, 3, points);
  const auto errorOf = [](const std::string& file) { return decode(file).error; };
  EXPECT_EQ(errorOf(good), "");
  EXPECT_NE(errorOf(good.substr(0, good.size() - 5)).find("truncated"), std::string::npos);
  EXPECT_NE(errorOf(good.substr(0, 100)).find("too short"), std::string::npos);
  std::string wrong = good;
  Bytes count;
  count.data = wrong;
  count.at(107, static_cast<std::uint32_t>(points.size() + 1)); // one point more than the file holds
  EXPECT_NE(errorOf(count.data).find("wrong point count"), std::string::npos) << errorOf(count.data);
  std::string notLas = good;
  notLas[0] = 'X';
  EXPECT_NE(errorOf(notLas).find("not a LAS file"), std::string::npos);
  // What it is by its content: a PLY file named .las.
  const std::string ply = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n" +
    std::string(300, ' ');
  EXPECT_NE(errorOf(ply).find("by its content a PLY file"), std::string::npos) << errorOf(ply);
  std::string laz = good;
  laz[104] = static_cast<char>(3 | 0x80);
  EXPECT_NE(errorOf(laz).find("LAZ"), std::string::npos);
  std::string format = good;
  format[104] = 11;
  EXPECT_NE(errorOf(format).find("point data record format 11"), std::string::npos);
  std::string version = good;
  version[25] = 5;
  EXPECT_NE(errorOf(version).find("version 1.5"), std::string::npos);
  // A header whose bounds the points leave (the max x lowered by a metre), which no unscaled reading explains.
  std::string bounds = good;
  double maxX;
  std::memcpy(&maxX, &bounds[179], 8);
  maxX -= 1.0;
  std::memcpy(&bounds[179], &maxX, 8);
  EXPECT_NE(errorOf(bounds).find("outside the header"), std::string::npos) << errorOf(bounds);
  // Records shorter than the format.
  std::string shortRecords = good;
  shortRecords[105] = 20;
  EXPECT_NE(errorOf(shortRecords).find("below the 34 of format 3"), std::string::npos) << errorOf(shortRecords);
  // An Extra Bytes type that does not exist.
  LasOptions badType;
  badType.extraType = 31;
  EXPECT_NE(errorOf(lasFile(4, 6, points, badType)).find("data type 31"), std::string::npos);
}
