// The text point-cloud parser: formats, headers, separators, and clear errors with line numbers.
#include "gls/PointTextParser.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace
{

gls::PointText parse(const std::string& s)
{
  return gls::parsePointText(s.data(), s.size());
}

} // namespace

TEST(PointTextParser, ReadsThreeAndSixColumnsWithAnySeparator)
{
  const auto a = parse("# a comment\n1 2 3\n4\t5\t6  # trailing comment\n\n7,8,9\n");
  ASSERT_TRUE(a.error.empty()) << a.error;
  EXPECT_EQ(a.points, (std::vector<double>{ 1, 2, 3, 4, 5, 6, 7, 8, 9 }));
  EXPECT_TRUE(a.normals.empty());
  const auto b = parse("1;2;3;0;0;1\r\n-1e3 +2.5 .5 1 0 0\r\n");
  ASSERT_TRUE(b.error.empty()) << b.error;
  EXPECT_EQ(b.points, (std::vector<double>{ 1, 2, 3, -1000, 2.5, 0.5 }));
  EXPECT_EQ(b.normals, (std::vector<double>{ 0, 0, 1, 1, 0, 0 }));
  const auto c = parse("1 2 nan\n");
  ASSERT_TRUE(c.error.empty());
  EXPECT_TRUE(std::isnan(c.points[2])); // non-finite values are kept: the filters leave such points out
}

TEST(PointTextParser, HeaderNamesTheColumns)
{
  const auto a = parse("id,Z,intensity,X,Y,NX,NY,NZ\n7,3,0.5,1,2,0,1,0\n");
  ASSERT_TRUE(a.error.empty()) << a.error;
  EXPECT_EQ(a.points, (std::vector<double>{ 1, 2, 3 }));
  EXPECT_EQ(a.normals, (std::vector<double>{ 0, 1, 0 }));
}

TEST(PointTextParser, MalformedInputGivesTheLine)
{
  EXPECT_EQ(parse("1 2 3\n4 5\n").error, "line 2: expected 3 columns like the lines before, got 2");
  EXPECT_EQ(parse("1 2 3 4\n").error,
    "line 1: expected 3 (x y z) or 6 (x y z nx ny nz) columns, or a header naming them; got 4");
  EXPECT_EQ(parse("1 2 3\n4 5 six\n").error, "line 2: not a number in '4 5...'");
  EXPECT_EQ(parse("a b c\n1 2 3\n").error, "line 1: a header line must name the columns x, y and z");
  EXPECT_EQ(parse("x y z nx\n").error, "line 1: a header naming normals must name all of nx, ny and nz");
  EXPECT_EQ(parse("# nothing\n\n").error, "line 2: no points found");
  EXPECT_EQ(parse("").error, "line 0: no points found");
  EXPECT_NE(gls::readPointTextFile("/nonexistent/cloud.xyz").error.find("cannot be opened"), std::string::npos);
}
