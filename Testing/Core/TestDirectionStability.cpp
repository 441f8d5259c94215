// The steadiest principal direction over scales (DirectionStability.h), on curvatures made by hand: the pair of scales
// whose d1 turn least per unit of log t, the anisotropy and shape index there, ridges and valleys, and no answer
// where no pair is anisotropic.
#include "gls/DirectionStability.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace
{

constexpr double kPi = 3.14159265358979323846;

/// Curvatures k1, k2 with d1 at angle `angle` in the xy-plane (normal z).
gls::PrincipalCurvatures at(double k1, double k2, double angle)
{
  const gls::Vec3 d1{ std::cos(angle), std::sin(angle), 0.0 };
  return { k1, k2, d1, gls::cross(gls::Vec3{ 0.0, 0.0, 1.0 }, d1) };
}

} // namespace

TEST(DirectionStability, PicksThePairOfScalesWhoseDirectionTurnsLeastPerLogScale)
{
  // Scales doubling; d1 turns 20, 5, 1 and 10 degrees between them: the third pair, at sqrt(4 * 8).
  const std::vector<double> scales{ 1.0, 2.0, 4.0, 8.0, 16.0 };
  const double deg = kPi / 180.0;
  const std::vector<gls::PrincipalCurvatures> c{ at(1.0, 0.0, 0.0), at(1.0, 0.0, 20 * deg), at(1.0, 0.0, 25 * deg),
    at(1.0, 0.0, 26 * deg), at(1.0, 0.0, 36 * deg) };
  const gls::StableDirection s = gls::steadiestDirection(c.data(), scales.data(), 5);
  EXPECT_NEAR(s.scale, std::sqrt(32.0), 1e-12);
  EXPECT_NEAR(s.turnRate, 1 * deg / std::log(2.0), 1e-12);
  EXPECT_NEAR(s.anisotropy, 1.0, 1e-15);
  EXPECT_NEAR(s.shapeIndex, 0.5, 1e-12); // a cylinder's: a ridge
  EXPECT_EQ(s.ridgeValley, 1.0);
  EXPECT_NEAR(s.direction.x, std::cos(25.5 * deg), 1e-12); // the mean of the pair's directions
  EXPECT_NEAR(s.direction.y, std::sin(25.5 * deg), 1e-12);
}

TEST(DirectionStability, DirectionsAreLinesAndUnevenScalesAreWeighedByLogScale)
{
  // d1 and -d1 are one direction; a turn of 2 degrees over a factor 4 of scale is steadier than 1.5 over a factor 2.
  const double deg = kPi / 180.0;
  const std::vector<double> scales{ 1.0, 2.0, 8.0 };
  std::vector<gls::PrincipalCurvatures> c{ at(2.0, -1.0, 0.0), at(2.0, -1.0, 181.5 * deg), at(2.0, -1.0, 3.5 * deg) };
  const gls::StableDirection s = gls::steadiestDirection(c.data(), scales.data(), 3);
  EXPECT_NEAR(s.scale, 4.0, 1e-12);
  EXPECT_NEAR(s.turnRate, 2 * deg / std::log(4.0), 1e-12);
  EXPECT_NEAR(s.anisotropy, 1.0, 1e-15);
  EXPECT_NEAR(s.shapeIndex, (2.0 / kPi) * std::atan(1.0 / 3.0), 1e-12); // a saddle ridge, not a ridge
  EXPECT_EQ(s.ridgeValley, 0.0);
}

TEST(DirectionStability, ValleysAndNoAnswerWhereNoPairIsAnisotropic)
{
  const std::vector<double> scales{ 1.0, 2.0, 4.0 };
  // Inward normals on a cylinder: k1 = 0, k2 = -1, a valley.
  std::vector<gls::PrincipalCurvatures> valley{ at(0.0, -1.0, 0.3), at(0.0, -1.0, 0.3), at(0.0, -1.0, 0.3) };
  const gls::StableDirection v = gls::steadiestDirection(valley.data(), scales.data(), 3);
  EXPECT_NEAR(v.shapeIndex, -0.5, 1e-12);
  EXPECT_EQ(v.ridgeValley, -1.0);
  EXPECT_EQ(v.turnRate, 0.0);
  EXPECT_NEAR(v.scale, std::sqrt(2.0), 1e-12); // the first of the equally steady pairs
  // Nearly umbilic (k1 - k2 below a fifth of the larger), or every other scale anisotropic: no pair counts.
  std::vector<gls::PrincipalCurvatures> round{ at(1.0, 0.9, 0.0), at(1.0, 0.0, 0.1), at(1.0, 0.95, 0.2) };
  const gls::StableDirection r = gls::steadiestDirection(round.data(), scales.data(), 3);
  EXPECT_TRUE(std::isnan(r.scale) && std::isnan(r.turnRate) && std::isnan(r.anisotropy));
  EXPECT_TRUE(std::isnan(r.shapeIndex) && std::isnan(r.direction.x) && std::isnan(r.ridgeValley));
  // Undefined directions (a sphere's NaN d1) count as not anisotropic.
  std::vector<gls::PrincipalCurvatures> sphere(3, gls::undefinedCurvatures());
  EXPECT_TRUE(std::isnan(gls::steadiestDirection(sphere.data(), scales.data(), 3).scale));
  EXPECT_TRUE(std::isnan(gls::steadiestDirection(sphere.data(), scales.data(), 1).scale));
}
