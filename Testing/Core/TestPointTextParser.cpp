// The text point-cloud parser: the standard layouts without a header (normals and colours told apart by their
// values), headers, separators and decimal commas, point-count lines, and clear errors with line numbers.
#include "gls/PointTextParser.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace
{

gls::PointText parse(const std::string& s)
{
  return gls::parsePointText(s.data(), s.size());
}

using Bytes = std::vector<unsigned char>;
using Doubles = std::vector<double>;
using Floats = std::vector<float>;

bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

} // namespace

TEST(PointTextParser, ThreeAndFourColumnsAreXyzAndIntensity)
{
  const auto a = parse("# a comment\n1 2 3\n4\t5\t6  # trailing comment\n\n-1e3 +2.5 .5\n");
  ASSERT_TRUE(a.error.empty()) << a.error;
  EXPECT_EQ(a.points, (Doubles{ 1, 2, 3, 4, 5, 6, -1000, 2.5, 0.5 }));
  EXPECT_TRUE(a.normals.empty() && a.colors.empty() && a.intensity.empty() && a.otherColumns.empty());
  EXPECT_EQ(a.layout, "x y z (3 columns, no header)");
  const auto b = parse("1 2 3 0.5\n4 5 6 -7\n");
  ASSERT_TRUE(b.error.empty()) << b.error;
  EXPECT_EQ(b.points, (Doubles{ 1, 2, 3, 4, 5, 6 }));
  EXPECT_EQ(b.intensity, (Floats{ 0.5f, -7.0f }));
  EXPECT_TRUE(b.normals.empty());
  const auto c = parse("1 2 nan\n");
  ASSERT_TRUE(c.error.empty());
  EXPECT_TRUE(std::isnan(c.points[2])); // non-finite values are kept: the filters leave such points out
}

TEST(PointTextParser, SixColumnsAreNormalsWhenUnitAndColoursWhenBytes)
{
  // Unit vectors (a zero normal allowed): normals, as given; the zero one is counted in the warning.
  const auto n = parse("0 0 0 0 0 1\n1 0 0 0.6 -0.8 0\n2 0 0 0 0 0\n3 0 0 0.577 0.577 0.577\n");
  ASSERT_TRUE(n.error.empty()) << n.error;
  EXPECT_EQ(n.normals, (Doubles{ 0, 0, 1, 0.6, -0.8, 0, 0, 0, 0, 0.577, 0.577, 0.577 }));
  EXPECT_TRUE(n.colors.empty());
  EXPECT_EQ(n.layout, "x y z nx ny nz (6 columns, no header: unit vectors, so normals)");
  EXPECT_TRUE(contains(n.warning, "1 of 4 normals have a length far from 1")) << n.warning;
  EXPECT_TRUE(contains(n.warning, "the first at line 3: 0")) << n.warning;

  // x y z r g b: the case (colour vectors of length 100 to 400 read as normals) -> colours, no normals.
  const auto c = parse("0 0 0 255 128 0\n1 0 0 10 20 30\n2 0 0 200 200 200\n");
  ASSERT_TRUE(c.error.empty()) << c.error;
  EXPECT_EQ(c.points, (Doubles{ 0, 0, 0, 1, 0, 0, 2, 0, 0 }));
  EXPECT_EQ(c.colors, (Bytes{ 255, 128, 0, 10, 20, 30, 200, 200, 200 }));
  EXPECT_TRUE(c.normals.empty());
  EXPECT_TRUE(c.warning.empty());
  EXPECT_EQ(c.layout, "x y z r g b (6 columns, no header: 0-255 integers, so colours)");

  // Neither (0-1 colours or unnormalized normals look alike): an error naming the way out.
  EXPECT_EQ(parse("0 0 0 0.5 0.5 0.5\n1 0 0 0.25 0 1\n").error,
    "line 1: 6 columns without a header, but columns 4-6 are neither unit normals (line 1: length 0.866025) nor "
    "0-255 integer colours (line 1: 0.5); add a header line naming the columns, e.g. 'x y z nx ny nz' or "
    "'x y z r g b'");
  EXPECT_TRUE(contains(parse("0 0 0 0 0 2\n1 0 0 0 -1 0\n").error, "neither unit normals (line 1: length 2)"));
}

TEST(PointTextParser, LeicaPtsAndNineColumnLayouts)
{
  // Leica PTS: a point-count line, then x y z intensity r g b.
  const auto l = parse("3\n1 2 3 -1024 255 0 0\n4 5 6 0 0 255 0\n7 8 9 2047 1 2 3\n");
  ASSERT_TRUE(l.error.empty()) << l.error;
  EXPECT_EQ(l.points, (Doubles{ 1, 2, 3, 4, 5, 6, 7, 8, 9 }));
  EXPECT_EQ(l.intensity, (Floats{ -1024, 0, 2047 }));
  EXPECT_EQ(l.colors, (Bytes{ 255, 0, 0, 0, 255, 0, 1, 2, 3 }));
  EXPECT_TRUE(l.normals.empty());
  EXPECT_EQ(l.layout, "x y z intensity r g b (7 columns, no header: Leica PTS); 1 point count line");
  // ... and x y z intensity.
  const auto li = parse("2\n1 2 3 -5\n4 5 6 7\n");
  ASSERT_TRUE(li.error.empty()) << li.error;
  EXPECT_EQ(li.intensity, (Floats{ -5, 7 }));
  EXPECT_TRUE(contains(parse("1 2 3 4 0.5 -0.5 0\n").error,
    "line 1: 7 columns without a header are read as x y z intensity r g b (Leica PTS), but columns 5-7 are not "
    "colours (line 1: 0.5); add a header line"));

  // Nine columns: CloudCompare's order (colours, then normals) and the other one, told apart by the values.
  const auto cc = parse("0 0 0 255 0 0 0 0 1\n1 1 1 0 255 7 1 0 0\n");
  ASSERT_TRUE(cc.error.empty()) << cc.error;
  EXPECT_EQ(cc.colors, (Bytes{ 255, 0, 0, 0, 255, 7 }));
  EXPECT_EQ(cc.normals, (Doubles{ 0, 0, 1, 1, 0, 0 }));
  EXPECT_EQ(cc.layout, "x y z r g b nx ny nz (9 columns, no header: CloudCompare's order)");
  const auto nc = parse("0 0 0 0 0 -1 0.5 0.25 1\n1 1 1 0 1 0 0 0 0\n");
  ASSERT_TRUE(nc.error.empty()) << nc.error;
  EXPECT_EQ(nc.normals, (Doubles{ 0, 0, -1, 0, 1, 0 }));
  EXPECT_EQ(nc.colors, (Bytes{ 128, 64, 255, 0, 0, 0 })); // fractions, times 255, rounded
  EXPECT_EQ(nc.layout, "x y z nx ny nz r g b (9 columns, no header); colours as 0-1 fractions");
  EXPECT_TRUE(contains(parse("0 0 0 1 0 0 0 1 0\n").error, "both columns 4-6 and 7-9 could be the normals"));
  EXPECT_TRUE(contains(parse("0 0 0 2 0 0 0 3 0\n").error, "neither columns 4-6 nor 7-9 are unit normals"));

  EXPECT_EQ(parse("1 2 3 4 5\n").error,
    "line 1: 5 columns without a header: expected 3 (x y z), 4 (x y z intensity), 6 (x y z nx ny nz, or x y z r g "
    "b), 7 (x y z intensity r g b) or 9 (x y z r g b nx ny nz, or x y z nx ny nz r g b), or a header line naming "
    "the columns");
}

TEST(PointTextParser, HeaderNamesTheColumns)
{
  const auto a = parse("id,Z,intensity,X,Y,NX,NY,NZ\n7,3,0.5,1,2,0,1,0\n8,6,1.5,4,5,1,0,0\n");
  ASSERT_TRUE(a.error.empty()) << a.error;
  EXPECT_EQ(a.points, (Doubles{ 1, 2, 3, 4, 5, 6 }));
  EXPECT_EQ(a.normals, (Doubles{ 0, 1, 0, 1, 0, 0 }));
  EXPECT_EQ(a.intensity, (Floats{ 0.5f, 1.5f }));
  ASSERT_EQ(a.otherColumns.size(), 1u);
  EXPECT_EQ(a.otherColumns[0].name, "id");
  EXPECT_EQ(a.otherColumns[0].values, (Doubles{ 7, 8 }));
  EXPECT_EQ(a.layout, "id z intensity x y nx ny nz (header line 1)");

  // CloudCompare's ASCII export: "//" header, a point-count line, colours, a scalar field, then normals.
  const auto cc = parse("//X,Y,Z,R,G,B,Scalar_field,Nx,Ny,Nz\n2\n1,2,3,10,20,30,0.25,0,0,1\n4,5,6,0,0,0,-1,0,2,0\n");
  ASSERT_TRUE(cc.error.empty()) << cc.error;
  EXPECT_EQ(cc.colors, (Bytes{ 10, 20, 30, 0, 0, 0 }));
  EXPECT_EQ(cc.normals, (Doubles{ 0, 0, 1, 0, 2, 0 })); // as given
  ASSERT_EQ(cc.otherColumns.size(), 1u);
  EXPECT_EQ(cc.otherColumns[0].name, "Scalar_field");
  EXPECT_EQ(cc.otherColumns[0].values, (Doubles{ 0.25, -1 }));
  EXPECT_TRUE(contains(cc.warning, "1 of 2 normals have a length far from 1")) << cc.warning;
  EXPECT_TRUE(contains(cc.warning, "line 4: 2")) << cc.warning;

  // red green blue as 0-1 fractions, alpha kept as a column of its own.
  const auto f = parse("x y z red green blue alpha\n1 2 3 0.2 0.4 1 0.5\n");
  ASSERT_TRUE(f.error.empty()) << f.error;
  EXPECT_EQ(f.colors, (Bytes{ 51, 102, 255 }));
  ASSERT_EQ(f.otherColumns.size(), 1u);
  EXPECT_EQ(f.otherColumns[0].name, "alpha");
  EXPECT_EQ(f.layout, "x y z r g b alpha (header line 1); colours as 0-1 fractions");

  EXPECT_EQ(parse("x y z r g b\n1 2 3 300 0 0\n").error,
    "line 2: colour value 300: the colour columns must hold integers in [0, 255], or only fractions in [0, 1]");
  EXPECT_EQ(parse("x y z r g b\n1 2 3 0.5 0 0\n1 2 3 7 0 0\n").error,
    "line 2: colour value 0.5: the colour columns must hold integers in [0, 255], or only fractions in [0, 1]");
  EXPECT_EQ(parse("x y z x\n1 2 3 4\n").error, "line 1: columns 1 and 4 both name x");
  EXPECT_EQ(parse("x y z r g\n1 2 3 4 5\n").error,
    "line 1: a header naming colours must name all of r, g and b (or red, green, blue)");
}

TEST(PointTextParser, SeparatorsAndDecimalCommas)
{
  // European CSV: ';' between fields, decimal commas.
  const auto eu = parse("x;y;z\n1,5;-2,25;3\n4;5;6,125\n");
  ASSERT_TRUE(eu.error.empty()) << eu.error;
  EXPECT_EQ(eu.points, (Doubles{ 1.5, -2.25, 3, 4, 5, 6.125 }));
  EXPECT_EQ(eu.layout, "x y z (header line 1); decimal commas");
  const auto eu6 = parse("1,5;2,5;3,5;0;0;1\r\n");
  ASSERT_TRUE(eu6.error.empty()) << eu6.error;
  EXPECT_EQ(eu6.points, (Doubles{ 1.5, 2.5, 3.5 }));
  EXPECT_EQ(eu6.normals, (Doubles{ 0, 0, 1 }));
  // Blank-separated with decimal commas (not six numbers).
  const auto blanks = parse("1,5 2,5 3,5\n4\t5,75\t6\n");
  ASSERT_TRUE(blanks.error.empty()) << blanks.error;
  EXPECT_EQ(blanks.points, (Doubles{ 1.5, 2.5, 3.5, 4, 5.75, 6 }));
  // Comma-separated, with or without blanks, quotes, a byte-order mark, a trailing delimiter.
  const auto csv = parse("\xEF\xBB\xBF\"x\",\"y\",\"z\"\n1, 2, 3\n\"4.5\",5,6,\n");
  ASSERT_TRUE(csv.error.empty()) << csv.error;
  EXPECT_EQ(csv.points, (Doubles{ 1, 2, 3, 4.5, 5, 6 }));
  EXPECT_EQ(csv.layout, "x y z (header line 1)");

  EXPECT_EQ(parse("1;2;3\n1,2,3\n").error,
    "line 2: not a number in column 1: '1,2,3'; this file's fields are separated by ';', with decimal commas "
    "allowed");
  EXPECT_EQ(parse("1,2,3\n1 2 3\n").error,
    "line 2: not a number in column 1: '1 2 3'; this file's fields are separated by ','");
  EXPECT_EQ(parse("1,,3\n").error, "line 1: empty field in column 2");
  EXPECT_EQ(parse("1;2,5,5;3\n").error, "line 1: not a number in column 2: '2,5,5'");
}

TEST(PointTextParser, PointCountLinesAreChecked)
{
  const auto two = parse("2\n0 0 0 1\n1 0 0 2\n1\n0 1 0 3\n");
  ASSERT_TRUE(two.error.empty()) << two.error;
  EXPECT_EQ(two.points, (Doubles{ 0, 0, 0, 1, 0, 0, 0, 1, 0 }));
  EXPECT_EQ(two.intensity, (Floats{ 1, 2, 3 }));
  EXPECT_EQ(two.layout, "x y z intensity (4 columns, no header); 2 point count lines");
  EXPECT_EQ(parse("3\n0 0 0\n1 1 1\n").error, "line 1: the point count line says 3 points, but 2 follow");
  EXPECT_EQ(parse("1\n0 0 0\n1 1 1\n2\n0 0 0\n").error, "line 1: the point count line says 1 point, but 2 follow");
}

TEST(PointTextParser, MalformedInputGivesTheLine)
{
  EXPECT_EQ(parse("1 2 3\n4 5\n").error, "line 2: expected 3 columns like the lines before, got 2");
  EXPECT_EQ(parse("x y z\n4 5\n").error, "line 2: expected 3 columns as the header line names, got 2");
  EXPECT_EQ(parse("1 2 3\n4 5 six\n").error,
    "line 2: not a number in column 3: 'six'; this file's fields are separated by blanks, with decimal commas "
    "allowed");
  EXPECT_EQ(parse("a b c\n1 2 3\n").error, "line 1: a header line must name the columns x, y and z");
  EXPECT_EQ(parse("x y z nx\n1 2 3 4\n").error, "line 1: a header naming normals must name all of nx, ny and nz");
  EXPECT_EQ(parse("x y z\n1 2 3\nx y z\n").error,
    "line 3: not a number in column 1: 'x'; this file's fields are separated by blanks, with decimal commas "
    "allowed");
  EXPECT_EQ(parse("# nothing\n\n").error, "line 2: no points found");
  EXPECT_EQ(parse("x y z\n").error, "line 1: no points found");
  EXPECT_EQ(parse("").error, "line 0: no points found");
  EXPECT_TRUE(parse("1 2 3\n4 5\n").points.empty());
  EXPECT_NE(gls::readPointTextFile("/nonexistent/cloud.xyz").error.find("cannot be opened"), std::string::npos);
}

namespace
{

/// Scan 1: identity, scanner at the origin, 2 x 2 points, one missing return. Scan 2: rotated 90 degrees about z
/// (axes x -> y, y -> -x) and moved to (10, 0, 1), 3 x 1 points.
std::string twoScanPtx()
{
  return "2\n2\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n"
         "1 2 3 0.5 10 20 30\n0 0 0 0.5 0 0 0\n-1 0 2 0.25 1 2 3\n4 5 6 1 255 255 255\n"
         "3\n1\n10 0 1\n0 1 0\n-1 0 0\n0 0 1\n0 1 0 0\n-1 0 0 0\n0 0 1 0\n10 0 1 1\n"
         "1 0 0 0.1 7 8 9\n0 2 0 0.2 7 8 9\n1 1 1 0.3 7 8 9\n";
}

} // namespace

TEST(PtxParser, TwoRegisteredScansWithMissingReturnsAndTheirScanners)
{
  const std::string ptx = twoScanPtx();
  const gls::PointText t = gls::parsePtx(ptx.data(), ptx.size());
  ASSERT_EQ(t.error, "");
  const std::vector<double> expected = { 1, 2, 3, -1, 0, 2, 4, 5, 6, 10, 1, 1, 8, 0, 1, 9, 1, 2 };
  EXPECT_EQ(t.points, expected);
  EXPECT_EQ(t.intensity, (std::vector<float>{ 0.5f, 0.25f, 1.0f, 0.1f, 0.2f, 0.3f }));
  EXPECT_EQ(t.colors.size(), 18u);
  EXPECT_EQ(t.colors[0], 10);
  const std::vector<double> scanners = { 0, 0, 0, 0, 0, 0, 0, 0, 0, 10, 0, 1, 10, 0, 1, 10, 0, 1 };
  EXPECT_EQ(t.viewpoints, scanners);
  EXPECT_NE(t.layout.find("2 scans"), std::string::npos) << t.layout;
  EXPECT_NE(t.layout.find("1 missing returns"), std::string::npos) << t.layout;
}

TEST(PtxParser, DamagedFilesAreRefusedWithTheLine)
{
  const std::string header = "2\n2\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n";
  const auto errorOf = [](const std::string& text) { return gls::parsePtx(text.data(), text.size()).error; };
  EXPECT_NE(errorOf(header + "1 2 3 0.5\n1 1 1 0.5\n").find("truncated"), std::string::npos);
  EXPECT_NE(errorOf(header + "1 2 3 0.5\n1 1 1 0.5 1 2 3\n").find("with and without colours"), std::string::npos);
  EXPECT_NE(errorOf(header + "1 2 3\n").find("line 11"), std::string::npos) << errorOf(header + "1 2 3\n");
  EXPECT_NE(errorOf("x\n").find("line 1: not a number"), std::string::npos) << errorOf("x\n");
  EXPECT_NE(errorOf("2 2\n").find("column count"), std::string::npos);
  EXPECT_NE(errorOf("").find("no PTX scan"), std::string::npos);
  // A NUL byte is no number (it ended the line once: "2\0LAS" read as "2").
  const std::string nul = std::string("2\0LAS\n", 6) + header.substr(2);
  EXPECT_NE(errorOf(nul).find("line 1: not a number"), std::string::npos) << errorOf(nul);
  EXPECT_EQ(gls::textCloudFormat(nul.data(), nul.size()), gls::TextCloudFormat::PointText);
  EXPECT_EQ(gls::textCloudFormat(header.data(), header.size()), gls::TextCloudFormat::Ptx);
}

namespace
{

/// A PCD file of 3 points with x y z, normals, packed rgb (F, PCL's way), intensity and curvature, in `encoding`.
std::string pcdFile(const std::string& encoding)
{
  const float xyz[3][3] = { { 1, 2, 3 }, { -1, 0.5f, 2 }, { 0, 0, std::numeric_limits<float>::quiet_NaN() } };
  const float n[3][3] = { { 0, 0, 1 }, { 1, 0, 0 }, { 0, 1, 0 } };
  const std::uint32_t rgb[3] = { 0x102030, 0xff0000, 0x0000ff };
  const float intensity[3] = { 0.5f, 0.5f, 0.5f }, curvature[3] = { 0.1f, 0.2f, 0.3f };
  std::string s = "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n"
                  "FIELDS x y z normal_x normal_y normal_z rgb intensity curvature\nSIZE 4 4 4 4 4 4 4 4 4\n"
                  "TYPE F F F F F F F F F\nCOUNT 1 1 1 1 1 1 1 1 1\nWIDTH 3\nHEIGHT 1\nVIEWPOINT 5 6 7 1 0 0 0\n"
                  "POINTS 3\nDATA " + encoding + "\n";
  const auto asFloat = [](std::uint32_t bits) {
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
  };
  std::vector<std::vector<float>> columns = { {}, {}, {}, {}, {}, {}, {}, {}, {} };
  for (int p = 0; p < 3; ++p)
  {
    const float row[9] = { xyz[p][0], xyz[p][1], xyz[p][2], n[p][0], n[p][1], n[p][2], asFloat(rgb[p]),
      intensity[p], curvature[p] };
    for (int f = 0; f < 9; ++f)
    {
      columns[f].push_back(row[f]);
    }
  }
  const auto bytesOf = [](float f) { return std::string(reinterpret_cast<const char*>(&f), 4); };
  if (encoding == "ascii")
  {
    for (int p = 0; p < 3; ++p)
    {
      for (int f = 0; f < 9; ++f)
      {
        char buffer[64];
        std::snprintf(buffer, sizeof(buffer), "%.9g%s", static_cast<double>(columns[f][p]), f == 8 ? "\n" : " ");
        s += buffer;
      }
    }
  }
  else if (encoding == "binary")
  {
    for (int p = 0; p < 3; ++p)
    {
      for (int f = 0; f < 9; ++f)
      {
        s += bytesOf(columns[f][p]);
      }
    }
  }
  else
  {
    // Field-major, LZF: each column as one literal run, but the intensity (0.5 three times) as 4 literal bytes and a
    // back-reference 4 bytes back, 8 long.
    std::string plain, packed;
    for (int f = 0; f < 9; ++f)
    {
      std::string column;
      for (int p = 0; p < 3; ++p)
      {
        column += bytesOf(columns[f][p]);
      }
      plain += column;
      if (f == 7)
      {
        packed += static_cast<char>(3) + column.substr(0, 4);
        packed += static_cast<char>(6 << 5) + std::string(1, static_cast<char>(3)); // length 6 + 2, back 3 + 1
      }
      else
      {
        packed += static_cast<char>(column.size() - 1) + column;
      }
    }
    const std::uint32_t sizes[2] = { static_cast<std::uint32_t>(packed.size()),
      static_cast<std::uint32_t>(plain.size()) };
    s += std::string(reinterpret_cast<const char*>(sizes), 8) + packed;
  }
  return s;
}

} // namespace

TEST(PcdParser, AsciiBinaryAndCompressedGiveTheSameCloud)
{
  for (const std::string encoding : { "ascii", "binary", "binary_compressed" })
  {
    SCOPED_TRACE(encoding);
    const std::string file = pcdFile(encoding);
    const gls::PointText t = gls::parsePcd(file.data(), file.size());
    ASSERT_EQ(t.error, "");
    ASSERT_EQ(t.points.size(), 9u);
    EXPECT_EQ(t.points[0], 1.0);
    EXPECT_EQ(t.points[4], 0.5);
    EXPECT_TRUE(std::isnan(t.points[8])); // a NaN point is kept
    EXPECT_EQ(t.normals, (std::vector<double>{ 0, 0, 1, 1, 0, 0, 0, 1, 0 }));
    EXPECT_EQ(t.colors, (std::vector<unsigned char>{ 0x10, 0x20, 0x30, 0xff, 0, 0, 0, 0, 0xff }));
    EXPECT_EQ(t.intensity, (std::vector<float>{ 0.5f, 0.5f, 0.5f }));
    ASSERT_EQ(t.otherColumns.size(), 1u);
    EXPECT_EQ(t.otherColumns[0].name, "curvature");
    EXPECT_EQ(static_cast<float>(t.otherColumns[0].values[1]), 0.2f);
    EXPECT_TRUE(t.viewpoints.empty()); // one sensor for the file, not one per point
    ASSERT_TRUE(t.hasSensor);
    EXPECT_EQ(std::vector<double>(t.sensor, t.sensor + 3), (std::vector<double>{ 5, 6, 7 }));
  }
  // PCL's default VIEWPOINT, and a file without one, are a sensor at the origin (pcl::flipNormalTowardsViewpoint's
  // convention), whatever the rotation.
  std::string plain = pcdFile("ascii");
  const std::size_t at = plain.find("VIEWPOINT 5 6 7");
  ASSERT_NE(at, std::string::npos);
  const std::size_t end = plain.find('\n', at);
  for (const std::string line : { "VIEWPOINT 0 0 0 1 0 0 0", "VIEWPOINT 0 0 0 0 1 0 0", "" })
  {
    std::string file = plain;
    file.replace(at, end - at + 1, line.empty() ? "" : line + "\n");
    const gls::PointText t = gls::parsePcd(file.data(), file.size());
    ASSERT_EQ(t.error, "") << line;
    ASSERT_TRUE(t.hasSensor) << line;
    EXPECT_EQ(std::vector<double>(t.sensor, t.sensor + 3), (std::vector<double>{ 0, 0, 0 })) << line;
  }
}

TEST(PcdParser, FieldNamesAreComparedWithoutCase)
{
  // PDAL writes X Y Z Intensity; the first of two fields of one role is taken.
  const std::string file = "VERSION 0.7\nFIELDS X Y Z Intensity NORMAL_X normal_y Normal_Z\nSIZE 4 4 4 4 4 4 4\n"
                           "TYPE F F F F F F F\nCOUNT 1 1 1 1 1 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n"
                           "1 2 3 0.5 0 0 1\n";
  const gls::PointText t = gls::parsePcd(file.data(), file.size());
  ASSERT_EQ(t.error, "");
  EXPECT_EQ(t.points, (std::vector<double>{ 1, 2, 3 }));
  EXPECT_EQ(t.intensity, (std::vector<float>{ 0.5f }));
  EXPECT_EQ(t.normals, (std::vector<double>{ 0, 0, 1 }));
  const std::string missing = "FIELDS a b c\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\nDATA ascii\n1 2 3\n";
  EXPECT_NE(gls::parsePcd(missing.data(), missing.size()).error.find("no x, y and z"), std::string::npos);
}

TEST(PcdParser, IntegerColoursAreTheirLowThirtyTwoBits)
{
  // rgba as a signed I 4 is negative where alpha >= 128 (0xff102030 here); a U 8 rgb keeps its colour in the low bits.
  const std::int32_t rgba = static_cast<std::int32_t>(0xff102030u);
  const std::uint64_t wide = 0x1234500ff0000ull;
  std::string binary = "FIELDS x y z rgba\nSIZE 4 4 4 4\nTYPE F F F I\nPOINTS 1\nDATA binary\n";
  const float xyz[3] = { 1, 2, 3 };
  binary += std::string(reinterpret_cast<const char*>(xyz), 12) + std::string(reinterpret_cast<const char*>(&rgba), 4);
  std::string wideFile = "FIELDS x y z rgb\nSIZE 4 4 4 8\nTYPE F F F U\nPOINTS 1\nDATA binary\n";
  wideFile += std::string(reinterpret_cast<const char*>(xyz), 12) + std::string(reinterpret_cast<const char*>(&wide), 8);
  const std::string ascii = "FIELDS x y z rgba\nSIZE 4 4 4 4\nTYPE F F F I\nPOINTS 1\nDATA ascii\n1 2 3 " +
    std::to_string(rgba) + "\n";
  const std::vector<unsigned char> expected[3] = { { 0x10, 0x20, 0x30 }, { 0xff, 0, 0 }, { 0x10, 0x20, 0x30 } };
  int k = 0;
  for (const std::string& file : { binary, wideFile, ascii })
  {
    const gls::PointText t = gls::parsePcd(file.data(), file.size());
    ASSERT_EQ(t.error, "") << k;
    EXPECT_EQ(t.colors, expected[k]) << k;
    ++k;
  }
}

TEST(PcdParser, DamagedFilesAreRefusedWithWhatIsWrong)
{
  const auto errorOf = [](const std::string& file) { return gls::parsePcd(file.data(), file.size()).error; };
  const std::string binary = pcdFile("binary");
  EXPECT_NE(errorOf(binary.substr(0, binary.size() - 10)).find("truncated"), std::string::npos)
    << errorOf(binary.substr(0, binary.size() - 10));
  const std::string compressed = pcdFile("binary_compressed");
  std::string damaged = compressed;
  const std::string data = "DATA binary_compressed\n";
  damaged[damaged.find(data) + data.size() + 8] = static_cast<char>(0xe0); // a back-reference before the start
  EXPECT_NE(errorOf(damaged).find("damaged binary_compressed (LZF) data"), std::string::npos) << errorOf(damaged);
  std::string many = binary;
  many.replace(many.find("POINTS 3"), 8, "POINTS 3000000");
  EXPECT_NE(errorOf(many).find("more than the file holds"), std::string::npos) << errorOf(many);
  EXPECT_NE(errorOf("VERSION 0.7\nFIELDS a b\nDATA ascii\n").find("no x, y and z"), std::string::npos);
  EXPECT_NE(errorOf("FIELDS x y z\nDATA zip\n").find("DATA 'zip'"), std::string::npos);
  EXPECT_NE(errorOf("hello\n").find("unknown PCD header line"), std::string::npos);
}

namespace
{

std::string writeTemp(const std::string& name, const std::string& bytes)
{
  const std::string path = testing::TempDir() + name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

gls::TextCloudFormat formatOf(const std::string& text)
{
  return gls::textCloudFormat(text.data(), text.size());
}

std::string headError(const std::string& text, bool wholeFile)
{
  return gls::pointCloudHeadError(text.data(), text.size(), wholeFile);
}

} // namespace

TEST(TextCloudFormat, TheContentTellsPcdAndPtxFilesWhateverTheirExtension)
{
  for (const std::string encoding : { "ascii", "binary", "binary_compressed" })
  {
    EXPECT_EQ(formatOf(pcdFile(encoding)), gls::TextCloudFormat::Pcd) << encoding;
  }
  EXPECT_EQ(formatOf("FIELDS x y z\nDATA ascii\n"), gls::TextCloudFormat::Pcd);
  // The count a PCD header announces (the main job's memory check reads it before the file).
  const std::string announced = pcdFile("binary_compressed");
  EXPECT_EQ(gls::pcdAnnouncedPoints(announced.data(), announced.size()), 3);
  const std::string noPoints = "FIELDS x y z\nWIDTH 4\nHEIGHT 2\nDATA ascii\n";
  EXPECT_EQ(gls::pcdAnnouncedPoints(noPoints.data(), noPoints.size()), 8);
  EXPECT_EQ(gls::pcdAnnouncedPoints("x y z\n1 2 3\n", 12), -1);
  EXPECT_EQ(formatOf(twoScanPtx()), gls::TextCloudFormat::Ptx);
  EXPECT_EQ(formatOf("2\n0 0 0 1\n1 0 0 2\n"), gls::TextCloudFormat::PointText);      // Leica PTS
  EXPECT_EQ(formatOf("2\n2\n0 0 0\n1 0 0\n0 1 0\n"), gls::TextCloudFormat::PointText); // short of a PTX header
  EXPECT_EQ(formatOf("x y z\n1 2 3\n"), gls::TextCloudFormat::PointText);
  EXPECT_EQ(formatOf("# VERSION\n1 2 3\n"), gls::TextCloudFormat::PointText);
  EXPECT_EQ(formatOf("\"\" VERSION\n\"\"\n"), gls::TextCloudFormat::PointText); // an empty quoted first field

  // A scan renamed .txt or .csv is read by its format's parser, and its layout says so.
  const std::string pcd = pcdFile("binary_compressed"), ptx = twoScanPtx();
  const gls::PointText fromPcd = gls::readPointTextFile(writeTemp("renamed-pcd.txt", pcd));
  ASSERT_EQ(fromPcd.error, "");
  const gls::PointText pcdParsed = gls::parsePcd(pcd.data(), pcd.size());
  EXPECT_EQ(fromPcd.normals, pcdParsed.normals);
  EXPECT_EQ(fromPcd.viewpoints, pcdParsed.viewpoints);
  EXPECT_EQ(fromPcd.layout, "a PCL PCD file by its content: " + pcdParsed.layout);
  const gls::PointText fromPtx = gls::readPointTextFile(writeTemp("renamed-ptx.csv", ptx));
  ASSERT_EQ(fromPtx.error, "");
  const gls::PointText ptxParsed = gls::parsePtx(ptx.data(), ptx.size());
  EXPECT_EQ(fromPtx.points, ptxParsed.points);
  EXPECT_EQ(fromPtx.viewpoints, ptxParsed.viewpoints);
  EXPECT_EQ(fromPtx.layout, "a Leica PTX file by its content: " + ptxParsed.layout);
  // A damaged one: the error names the format the content showed.
  const std::string path = writeTemp("damaged-pcd.txt", pcd.substr(0, pcd.size() - 10));
  EXPECT_EQ(gls::readPointTextFile(path).error.rfind(path + ": a PCL PCD file by its content: ", 0), 0u)
    << gls::readPointTextFile(path).error;
}

TEST(TextCloudFormat, AFilesFirstLinesTellAPointCloudFromATable)
{
  EXPECT_EQ(headError("x,y,z,speed\n1,2,3,4\n", true), "");
  EXPECT_EQ(headError("0 0 0\n1 0 0\n", true), "");
  EXPECT_EQ(headError(pcdFile("binary"), false), "");
  EXPECT_EQ(headError(twoScanPtx().substr(0, 70), false), "");
  // Tables that are no point cloud: the parser's own error.
  for (const std::string table : { "time,value\n1,2\n3,4\n", "a,b,c\n1,2,3\n", "1,2\n3,4\n", "name,x,y,z\nP1,1,2,3\n" })
  {
    EXPECT_NE(headError(table, true), "") << table;
    EXPECT_EQ(headError(table, true), parse(table).error) << table;
  }
  // Only complete lines of a file's first bytes are judged; its last point-count group may go on after them.
  EXPECT_EQ(headError("0 0 0\n1 0 0\n1 2", false), "");
  EXPECT_EQ(headError("0 0 0\n1 0 0\n1 2", true), "line 3: expected 3 columns like the lines before, got 2");
  EXPECT_EQ(headError("3\n0 0 0 1\n1 0 0 2\n", false), "");
  EXPECT_EQ(headError("3\n0 0 0 1\n1 0 0 2\n", true), "line 1: the point count line says 3 points, but 2 follow");
  EXPECT_EQ(headError("1\n0 0 0 1\n1 0 0 2\n", false), "line 1: the point count line says 1 point, but 2 follow");
  EXPECT_EQ(headError("1 2 3", false), "no line ends in the first 5 bytes");

  // A file: its first pointCloudHeadBytes; a count line announcing more points than they hold is no error there.
  std::string big = "200000\n";
  for (int i = 0; big.size() < 2 * gls::pointCloudHeadBytes; ++i)
  {
    big += std::to_string(i) + " 0.5 1 7\n";
  }
  EXPECT_EQ(gls::pointCloudFileHeadError(writeTemp("big-head.txt", big)), "");
  EXPECT_NE(parse(big).error, ""); // the whole file holds fewer than 200000
  const std::string path = writeTemp("table.csv", "time,value\n1,2\n");
  EXPECT_EQ(gls::pointCloudFileHeadError(path), path + ": " + parse("time,value\n1,2\n").error);
  EXPECT_NE(gls::pointCloudFileHeadError("/nonexistent/cloud.csv").find("cannot be opened"), std::string::npos);
}
