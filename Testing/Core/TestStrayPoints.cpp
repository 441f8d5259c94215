// Stray points (gls/StrayPoints.h): a lone return far from a scan is found; points of the scan, a small object
// standing apart and non-finite points are not.
#include "TestClouds.h"

#include "gls/StrayPoints.h"

#include <gtest/gtest.h>

#include <limits>

using namespace glstest;

TEST(StrayPoints, ALoneReturnIsFoundAndNothingOfTheScanIs)
{
  Cloud c = sampleObjSurface(dataFile("stanford-bunny.obj"), 40000, 3);
  EXPECT_TRUE(gls::findStrayPoints(c.points.data(), c.size()).empty()) << "the clean bunny";
  const std::size_t lone = c.size();
  c.add(10.0, 10.0, 10.0, 0.0, 0.0, 1.0); // the bunny is about 0.25 wide
  const double nan = std::numeric_limits<double>::quiet_NaN();
  c.add(nan, 0.0, 0.0, 0.0, 0.0, 1.0);
  // A small object 1 unit away: six points within a few millimetres of each other.
  for (int k = 0; k < 6; ++k)
  {
    c.add(1.0 + 0.001 * k, 0.5, 0.0, 0.0, 0.0, 1.0);
  }
  const std::vector<std::uint64_t> stray = gls::findStrayPoints(c.points.data(), c.size());
  ASSERT_EQ(stray.size(), 1u);
  EXPECT_EQ(stray[0], lone);
  // Two lone returns on either side.
  c.add(-7.0, 0.0, 3.0, 0.0, 0.0, 1.0);
  EXPECT_EQ(gls::findStrayPoints(c.points.data(), c.size()).size(), 2u);
  // Too few points for quantiles: none.
  EXPECT_TRUE(gls::findStrayPoints(c.points.data() + 3 * (c.size() - 60), 60).empty());
}
