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
};

std::vector<Point> somePoints()
{
  std::vector<Point> p;
  for (int i = 0; i < 7; ++i)
  {
    p.push_back({ 1000 * i - 3000, 20 * i + 5, -7 * i, static_cast<std::uint16_t>(100 + i), 1 + i % 3, 3,
      2 + i % 5, -12.0 + 3.0 * i, static_cast<std::uint8_t>(i), static_cast<std::uint16_t>(40 + i),
      1.0e5 + 0.25 * i, { static_cast<std::uint16_t>(256 * i), 7, 65535 }, static_cast<std::uint16_t>(900 + i),
      static_cast<std::int16_t>(-3 + i) });
  }
  return p;
}

const double kScale[3] = { 0.01, 0.01, 0.001 };
const double kOffset[3] = { 500000.0, 4000000.0, 100.0 };

/// A LAS 1.minor file of the points in `format`, optionally with an Extra Bytes record (one i16 field).
std::string lasFile(int minor, int format, const std::vector<Point>& points, bool extraBytes = false)
{
  const std::size_t headerSize = minor >= 4 ? 375 : (minor == 3 ? 235 : 227);
  const std::size_t base = gls::lasFormatSize(format);
  const std::size_t recordLength = base + (extraBytes ? 2 : 0);
  const std::size_t vlrLength = extraBytes ? 54 + 192 : 0;
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
  b.put<std::uint32_t>(extraBytes ? 1 : 0);
  b.put<std::uint8_t>(static_cast<std::uint8_t>(format));
  b.put<std::uint16_t>(static_cast<std::uint16_t>(recordLength));
  b.put<std::uint32_t>(static_cast<std::uint32_t>(points.size()));
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
      const double v = (a == 0 ? p.x : a == 1 ? p.y : p.z) * kScale[a] + kOffset[a];
      lo = std::min(lo, v);
      hi = std::max(hi, v);
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
    b.put<std::uint64_t>(0);
    b.put<std::uint32_t>(0);
    b.put<std::uint64_t>(points.size());
    for (int r = 0; r < 15; ++r)
    {
      b.put<std::uint64_t>(0);
    }
  }
  EXPECT_EQ(b.data.size(), headerSize);
  if (extraBytes)
  {
    b.put<std::uint16_t>(0);
    b.text("LASF_Spec", 16);
    b.put<std::uint16_t>(4);
    b.put<std::uint16_t>(192);
    b.text("extra bytes", 32);
    b.put<std::uint16_t>(0);
    b.put<std::uint8_t>(4);               // i16
    b.put<std::uint8_t>(8 | 16);          // scale and offset given
    b.text("Amplitude", 32);
    b.text("", 4);
    b.text("", 24 * 3);                   // no_data, min, max
    b.put<double>(0.5);
    b.text("", 16);                       // scale
    b.put<double>(1.0);
    b.text("", 16);                       // offset
    b.text("an amplitude", 32);
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
      b.put<std::uint8_t>(0);
      b.put<std::uint8_t>(static_cast<std::uint8_t>(p.classification));
      b.put<std::uint8_t>(p.user);
      b.put<std::int16_t>(static_cast<std::int16_t>(std::lround(p.scanAngle / 0.006)));
      b.put<std::uint16_t>(p.source);
      b.put<double>(p.gps);
    }
    else
    {
      b.put<std::uint8_t>(static_cast<std::uint8_t>(p.returnNumber | (p.returns << 3)));
      b.put<std::uint8_t>(static_cast<std::uint8_t>(p.classification | 0x80)); // the withheld flag set
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
    if (extraBytes)
    {
      b.put<std::int16_t>(p.extra);
    }
  }
  return b.data;
}

/// Reads a file from memory: the header and the points, or the error.
std::string readBack(const std::string& file, gls::LasHeader& h, std::vector<double>& xyz,
  std::vector<std::uint16_t>& intensity, std::vector<std::uint8_t>& returnNumber, std::vector<std::uint8_t>& returns,
  std::vector<std::uint8_t>& classification, std::vector<float>& angle, std::vector<double>& gps,
  std::vector<std::uint16_t>& rgb, std::vector<std::uint16_t>& nir, std::vector<double>& extra)
{
  std::istringstream in(file);
  std::string error;
  if (!gls::readLasHeader(in, file.size(), h, error))
  {
    return error;
  }
  const std::size_t n = static_cast<std::size_t>(h.pointCount);
  xyz.assign(3 * n, 0.0);
  intensity.assign(n, 0);
  returnNumber.assign(n, 0);
  returns.assign(n, 0);
  classification.assign(n, 0);
  angle.assign(n, 0.0f);
  gps.assign(n, -1.0);
  rgb.assign(3 * n, 0);
  nir.assign(n, 0);
  extra.assign(n, 0.0);
  gls::LasColumns c;
  c.xyz = xyz.data();
  c.intensity = intensity.data();
  c.returnNumber = returnNumber.data();
  c.numberOfReturns = returns.data();
  c.classification = classification.data();
  c.scanAngle = angle.data();
  c.gpsTime = gps.data();
  c.rgb = rgb.data();
  c.nir = nir.data();
  c.extra.push_back(extra.data());
  gls::LasReadResult read;
  if (!gls::readLasPoints(in, h, c, read, error))
  {
    return error;
  }
  return "";
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
        gls::LasHeader h;
        std::vector<double> xyz, gps, extra;
        std::vector<std::uint16_t> intensity, rgb, nir;
        std::vector<std::uint8_t> returnNumber, returns, classification;
        std::vector<float> angle;
        const std::string error = readBack(lasFile(minor, format, points, extraBytes), h, xyz, intensity,
          returnNumber, returns, classification, angle, gps, rgb, nir, extra);
        ASSERT_EQ(error, "");
        ASSERT_EQ(h.pointCount, points.size());
        ASSERT_EQ(h.extra.size(), extraBytes ? 1u : 0u);
        for (std::size_t i = 0; i < points.size(); ++i)
        {
          const Point& p = points[i];
          EXPECT_EQ(xyz[3 * i], p.x * kScale[0] + kOffset[0]);
          EXPECT_EQ(xyz[3 * i + 1], p.y * kScale[1] + kOffset[1]);
          EXPECT_EQ(xyz[3 * i + 2], p.z * kScale[2] + kOffset[2]);
          EXPECT_EQ(intensity[i], p.intensity);
          EXPECT_EQ(returnNumber[i], p.returnNumber);
          EXPECT_EQ(returns[i], p.returns);
          EXPECT_EQ(classification[i], p.classification); // without the withheld flag
          EXPECT_NEAR(angle[i], p.scanAngle, 0.004);
          EXPECT_EQ(gps[i], h.hasGpsTime() ? p.gps : -1.0);
          for (int a = 0; a < 3; ++a)
          {
            EXPECT_EQ(rgb[3 * i + a], h.hasRgb() ? p.rgb[a] : 0);
          }
          EXPECT_EQ(nir[i], h.hasNir() ? p.nir : 0);
          if (extraBytes)
          {
            EXPECT_EQ(h.extra[0].name, "Amplitude");
            EXPECT_EQ(extra[i], 0.5 * p.extra + 1.0);
          }
        }
      }
    }
  }
}

TEST(LasFile, DamagedFilesAreRefusedWithWhatIsWrong)
{
  const std::vector<Point> points = somePoints();
  const std::string good = lasFile(2, 3, points);
  const auto errorOf = [](const std::string& file) {
    gls::LasHeader h;
    std::vector<double> xyz, gps, extra;
    std::vector<std::uint16_t> intensity, rgb, nir;
    std::vector<std::uint8_t> returnNumber, returns, classification;
    std::vector<float> angle;
    return readBack(file, h, xyz, intensity, returnNumber, returns, classification, angle, gps, rgb, nir, extra);
  };
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
  std::string laz = good;
  laz[104] = static_cast<char>(3 | 0x80);
  EXPECT_NE(errorOf(laz).find("LAZ"), std::string::npos);
  std::string format = good;
  format[104] = 11;
  EXPECT_NE(errorOf(format).find("point data record format 11"), std::string::npos);
  std::string version = good;
  version[25] = 5;
  EXPECT_NE(errorOf(version).find("version 1.5"), std::string::npos);
  // A header whose bounds the points leave: the max x lowered by a metre.
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
}
