// LAS 1.4 files written by gls::writeLas read back by gls::readLasHeader / readLasPoints, every field, and checked
// byte by byte where the specification places them (ASPRS LAS 1.4 R15, tables 4, 10-12, 24).
#include "gls/LasFile.h"
#include "gls/LasWriter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace
{

/// n points of a survey tile at UTM-sized coordinates on a grid of the scale, with every attribute varied.
struct Tile
{
  std::size_t n = 50;
  std::vector<double> xyz, gps;
  std::vector<std::uint16_t> intensity, source, rgb, nir;
  std::vector<std::uint8_t> number, returns, cls, user, withheld, synthetic, key, overlap, direction, edge, channel;
  std::vector<float> angle, value;
  std::vector<double> vector3;

  Tile()
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      xyz.insert(xyz.end(), { 652000.0 + 0.001 * static_cast<double>(13 * i), 5410000.0 + 0.001 * static_cast<double>(
        7 * i), 100.0 + 0.001 * static_cast<double>(i % 9) });
      gps.push_back(3.0e5 + 0.125 * static_cast<double>(i));
      intensity.push_back(static_cast<std::uint16_t>(100 * i));
      source.push_back(static_cast<std::uint16_t>(i % 4));
      rgb.insert(rgb.end(), { static_cast<std::uint16_t>(257 * i), 7, 65535 });
      nir.push_back(static_cast<std::uint16_t>(3 * i));
      number.push_back(static_cast<std::uint8_t>(1 + i % 3));
      returns.push_back(3);
      cls.push_back(static_cast<std::uint8_t>(i % 20));
      user.push_back(static_cast<std::uint8_t>(i));
      withheld.push_back(static_cast<std::uint8_t>(i % 5 == 0));
      synthetic.push_back(static_cast<std::uint8_t>(i % 7 == 0));
      key.push_back(static_cast<std::uint8_t>(i % 3 == 0));
      overlap.push_back(static_cast<std::uint8_t>(i % 2));
      direction.push_back(static_cast<std::uint8_t>((i / 2) % 2));
      edge.push_back(static_cast<std::uint8_t>(i % 11 == 0));
      channel.push_back(static_cast<std::uint8_t>(i % 4));
      angle.push_back(static_cast<float>(-20.0 + 0.006 * static_cast<double>(100 * i)));
      value.push_back(0.25f * static_cast<float>(i));
      vector3.insert(vector3.end(), { 1.0, -0.5 * static_cast<double>(i), 1e-3 });
    }
  }

  gls::LasWriteSource source_(bool colours) const
  {
    gls::LasWriteSource s;
    s.n = n;
    s.xyz = xyz.data();
    for (int a = 0; a < 3; ++a)
    {
      s.scale[a] = 0.001;
    }
    s.offset[0] = 652000.0;
    s.offset[1] = 5410000.0;
    s.offset[2] = 0.0;
    s.intensity = intensity.data();
    s.returnNumber = number.data();
    s.numberOfReturns = returns.data();
    s.classification = cls.data();
    s.scanAngle = angle.data();
    s.userData = user.data();
    s.pointSourceId = source.data();
    s.gpsTime = gps.data();
    s.rgb = colours ? rgb.data() : nullptr;
    s.nir = colours ? nir.data() : nullptr;
    s.withheld = withheld.data();
    s.synthetic = synthetic.data();
    s.keyPoint = key.data();
    s.overlap = overlap.data();
    s.scanDirection = direction.data();
    s.edgeOfFlightLine = edge.data();
    s.scannerChannel = channel.data();
    gls::LasExtraSource f;
    f.name = "GLSFeature";
    f.description = "continuous feature";
    f.floats = value.data();
    gls::LasExtraSource v;
    v.name = "GLSStableDirection";
    v.components = 3;
    v.doubles = vector3.data();
    s.extra = { f, v };
    s.coordinateSystem.wkt = "PROJCS[\"WGS 84 / UTM zone 32N\"]";
    s.coordinateSystem.geoKeys = { 1, 1, 0, 1, 3072, 0, 1, 32632 };
    return s;
  }
};

} // namespace

TEST(LasWriter, WritesEveryFieldTheReaderReadsBack)
{
  const Tile t;
  for (const bool colours : { false, true })
  {
    SCOPED_TRACE(colours);
    std::ostringstream out;
    gls::LasWriteResult w;
    std::string error;
    ASSERT_TRUE(gls::writeLas(out, t.source_(colours), w, error)) << error;
    EXPECT_EQ(w.written, t.n);
    EXPECT_EQ(w.format, colours ? 8 : 6);
    const std::string file = out.str();
    std::istringstream in(file);
    gls::LasHeader h;
    ASSERT_TRUE(gls::readLasHeader(in, file.size(), h, error)) << error;
    EXPECT_TRUE(h.quirks.empty());
    EXPECT_EQ(h.versionMinor, 4);
    EXPECT_EQ(h.format, w.format);
    ASSERT_EQ(h.pointCount, t.n);
    EXPECT_EQ(h.coordinateSystem.wkt, "PROJCS[\"WGS 84 / UTM zone 32N\"]");
    EXPECT_EQ(h.coordinateSystem.geoKeys, (std::vector<std::uint16_t>{ 1, 1, 0, 1, 3072, 0, 1, 32632 }));
    ASSERT_EQ(h.extra.size(), 4u); // GLSFeature, GLSStableDirection_x, _y, _z
    EXPECT_EQ(h.extra[0].name, "GLSFeature");
    EXPECT_EQ(h.extra[3].name, "GLSStableDirection_z");
    std::vector<double> xyz(3 * t.n), gps(t.n), extra[4];
    std::vector<std::uint16_t> intensity(t.n), source(t.n), rgb(3 * t.n), nir(t.n);
    std::vector<std::uint8_t> number(t.n), returns(t.n), cls(t.n), user(t.n), withheld(t.n), synthetic(t.n),
      key(t.n), overlap(t.n), direction(t.n), edge(t.n), channel(t.n);
    std::vector<float> angle(t.n);
    gls::LasColumns c;
    c.xyz = xyz.data();
    c.gpsTime = gps.data();
    c.intensity = intensity.data();
    c.pointSourceId = source.data();
    c.rgb = rgb.data();
    c.nir = nir.data();
    c.returnNumber = number.data();
    c.numberOfReturns = returns.data();
    c.classification = cls.data();
    c.userData = user.data();
    c.withheld = withheld.data();
    c.synthetic = synthetic.data();
    c.keyPoint = key.data();
    c.overlap = overlap.data();
    c.scanDirection = direction.data();
    c.edgeOfFlightLine = edge.data();
    c.scannerChannel = channel.data();
    c.scanAngle = angle.data();
    for (auto& e : extra)
    {
      e.resize(t.n);
      c.extra.push_back(e.data());
    }
    gls::LasReadResult r;
    ASSERT_TRUE(gls::readLasPoints(in, h, c, r, error)) << error;
    EXPECT_EQ(xyz, t.xyz); // positions on the scale's grid come back exactly
    EXPECT_EQ(gps, t.gps);
    EXPECT_EQ(intensity, t.intensity);
    EXPECT_EQ(source, t.source);
    EXPECT_EQ(number, t.number);
    EXPECT_EQ(returns, t.returns);
    EXPECT_EQ(cls, t.cls);
    EXPECT_EQ(user, t.user);
    EXPECT_EQ(withheld, t.withheld);
    EXPECT_EQ(synthetic, t.synthetic);
    EXPECT_EQ(key, t.key);
    EXPECT_EQ(overlap, t.overlap);
    EXPECT_EQ(direction, t.direction);
    EXPECT_EQ(edge, t.edge);
    EXPECT_EQ(channel, t.channel);
    if (colours)
    {
      EXPECT_EQ(rgb, t.rgb);
      EXPECT_EQ(nir, t.nir);
    }
    for (std::size_t i = 0; i < t.n; ++i)
    {
      EXPECT_NEAR(angle[i], t.angle[i], 0.0031);
      EXPECT_EQ(extra[0][i], static_cast<double>(t.value[i]));
      for (int k = 0; k < 3; ++k)
      {
        EXPECT_EQ(extra[1 + k][i], static_cast<double>(static_cast<float>(t.vector3[3 * i + k])));
      }
    }
    EXPECT_EQ(r.withheld, 10u);
    // Where the specification puts them: the version, the format, the 64-bit count and the counts by return.
    EXPECT_EQ(file.substr(0, 4), "LASF");
    EXPECT_EQ(file[24], 1);
    EXPECT_EQ(file[25], 4);
    std::uint64_t count = 0, firstReturns = 0;
    std::memcpy(&count, &file[247], 8);
    std::memcpy(&firstReturns, &file[255], 8);
    EXPECT_EQ(count, t.n);
    EXPECT_EQ(firstReturns, 17u); // return number 1 at every third point
    std::uint16_t encoding = 0;
    std::memcpy(&encoding, &file[6], 2);
    EXPECT_EQ(encoding, 16); // the WKT bit
  }
}

TEST(LasWriter, ChoosesAScaleThatKeepsPositionsAndRefusesWhatDoesNotFit)
{
  // A 0.2 m object as float32 values: the finest power of ten the 32-bit integers allow, 1e-10: no position moves by
  // more than half of it; NaN positions are left out and counted.
  std::vector<double> xyz;
  for (int i = 0; i < 100; ++i)
  {
    xyz.insert(xyz.end(), { static_cast<double>(static_cast<float>(0.002 * i - 0.1)), 0.05, static_cast<double>(
      static_cast<float>(0.001 * i)) });
  }
  xyz.insert(xyz.end(), { std::nan(""), 0.0, 0.0 });
  gls::LasWriteSource s;
  s.n = xyz.size() / 3;
  s.xyz = xyz.data();
  ASSERT_TRUE(gls::chooseLasScaleAndOffset(xyz.data(), s.n, s.scale, s.offset));
  EXPECT_EQ(s.scale[0], 1e-10);
  EXPECT_EQ(s.offset[0], static_cast<double>(static_cast<float>(-0.1)));
  std::ostringstream out;
  gls::LasWriteResult w;
  std::string error;
  ASSERT_TRUE(gls::writeLas(out, s, w, error)) << error;
  EXPECT_EQ(w.written, 100u);
  EXPECT_EQ(w.leftOut, 1u);
  const std::string file = out.str();
  std::istringstream in(file);
  gls::LasHeader h;
  ASSERT_TRUE(gls::readLasHeader(in, file.size(), h, error)) << error;
  std::vector<double> back(3 * 100);
  gls::LasColumns c;
  c.xyz = back.data();
  gls::LasReadResult r;
  ASSERT_TRUE(gls::readLasPoints(in, h, c, r, error)) << error;
  for (std::size_t i = 0; i < 300; ++i)
  {
    EXPECT_LE(std::abs(back[i] - xyz[i]), 0.5e-10 + 1e-16) << i;
  }
  // A survey of 1 km at a micrometre: beyond the integers, refused with the point and the scale.
  const double wide[] = { 0.0, 0.0, 0.0, 3000.0, 0.0, 0.0 };
  gls::LasWriteSource tooWide;
  tooWide.n = 2;
  tooWide.xyz = wide;
  tooWide.scale[0] = 1e-6;
  EXPECT_FALSE(gls::writeLas(out, tooWide, w, error));
  EXPECT_NE(error.find("point 1's x = 3000 is beyond the 32-bit integers at the scale 9.99"), std::string::npos)
    << error;
  EXPECT_FALSE(gls::chooseLasScaleAndOffset(xyz.data() + 300, 1, s.scale, s.offset)); // no finite point
}
