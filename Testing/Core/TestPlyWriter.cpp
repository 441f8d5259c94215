// Binary PLY files written by gls::writePly, parsed here from the format's description (header lines, then the
// vertex and face records little endian): the properties named as CloudCompare loads them, the values, the faces
// renumbered around a left-out point.
#include "gls/PlyWriter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

namespace
{

/// A parsed PLY: its header lines and the bytes after end_header.
struct Parsed
{
  std::vector<std::string> header;
  std::string body;
};

Parsed parse(const std::string& file)
{
  Parsed p;
  std::size_t at = 0;
  while (at < file.size())
  {
    const std::size_t end = file.find('\n', at);
    const std::string line = file.substr(at, end - at);
    at = end + 1;
    p.header.push_back(line);
    if (line == "end_header")
    {
      break;
    }
  }
  p.body = file.substr(at);
  return p;
}

template <typename T>
T read(const std::string& body, std::size_t& at)
{
  T v;
  std::memcpy(&v, body.data() + at, sizeof(T));
  at += sizeof(T);
  return v;
}

} // namespace

TEST(PlyWriter, PointsNormalsColoursScalarsAndFacesAsTheFormatSays)
{
  const double nan = std::nan("");
  // Four points, the third a missing return; two triangles, the second using it.
  const std::vector<double> xyz = { 0, 0, 0, 1, 0, 0, nan, nan, nan, 0, 1, 0.5 };
  const std::vector<float> normals = { 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, -1 };
  const std::vector<std::uint8_t> colours = { 10, 20, 30, 40, 50, 60, 70, 80, 90, 255, 0, 1 };
  const std::vector<float> feature = { 0.25f, 0.5f, 0.75f, 1.0f };
  const std::vector<double> direction = { 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5, 0.5, 0 };
  gls::PlyWriteSource s;
  s.n = 4;
  s.xyz = xyz.data();
  s.normals = normals.data();
  s.colours = colours.data();
  gls::PlyScalarSource f;
  f.name = "GLSFeature";
  f.floats = feature.data();
  gls::PlyScalarSource d;
  d.name = "GLS Stable Direction"; // blanks written as '_'
  d.components = 3;
  d.doubles = direction.data();
  s.scalars = { f, d };
  s.faceOffsets = { 0, 3, 6 };
  s.faceIndices = { 0, 1, 3, 1, 2, 3 };
  s.comments = { "coordinate system: WGS 84" };
  for (const bool floats : { false, true })
  {
    SCOPED_TRACE(floats);
    s.floatPositions = floats;
    std::ostringstream out;
    gls::PlyWriteResult r;
    std::string error;
    ASSERT_TRUE(gls::writePly(out, s, r, error)) << error;
    EXPECT_EQ(r.written, 3u);
    EXPECT_EQ(r.leftOut, 1u);
    EXPECT_EQ(r.faces, 1u);
    EXPECT_EQ(r.facesLeftOut, 1u);
    const Parsed p = parse(out.str());
    const std::string t = floats ? "float" : "double";
    const std::vector<std::string> expected = { "ply", "format binary_little_endian 1.0",
      "comment coordinate system: WGS 84", "element vertex 3", "property " + t + " x", "property " + t + " y",
      "property " + t + " z", "property float nx", "property float ny", "property float nz", "property uchar red",
      "property uchar green", "property uchar blue", "property float scalar_GLSFeature",
      "property double scalar_GLS_Stable_Direction_x", "property double scalar_GLS_Stable_Direction_y",
      "property double scalar_GLS_Stable_Direction_z", "element face 1", "property list uchar int vertex_indices",
      "end_header" };
    EXPECT_EQ(p.header, expected);
    std::size_t at = 0;
    for (const int i : { 0, 1, 3 })
    {
      for (int a = 0; a < 3; ++a)
      {
        const double v = floats ? read<float>(p.body, at) : read<double>(p.body, at);
        EXPECT_EQ(v, floats ? static_cast<double>(static_cast<float>(xyz[3 * i + a])) : xyz[3 * i + a]);
      }
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_EQ(read<float>(p.body, at), normals[3 * i + a]);
      }
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_EQ(read<std::uint8_t>(p.body, at), colours[3 * i + a]);
      }
      EXPECT_EQ(read<float>(p.body, at), feature[i]);
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_EQ(read<double>(p.body, at), direction[3 * i + a]);
      }
    }
    EXPECT_EQ(read<std::uint8_t>(p.body, at), 3);
    EXPECT_EQ(read<std::int32_t>(p.body, at), 0);
    EXPECT_EQ(read<std::int32_t>(p.body, at), 1);
    EXPECT_EQ(read<std::int32_t>(p.body, at), 2); // point 3, the third written
    EXPECT_EQ(at, p.body.size());
  }
}
