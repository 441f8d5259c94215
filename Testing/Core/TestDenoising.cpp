// MLS projection and adaptive bandwidth in the core, against analytic oracles.
#include "TestClouds.h"

#include "gls/AdaptiveBandwidth.h"
#include "gls/MlsProjection.h"
#include "gls/NeighborGrid.h"
#include "gls/Projection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace
{

struct Projected
{
  std::vector<double> points, normals, displacement;
  std::vector<int> iterations;
  std::vector<unsigned char> converged;
  explicit Projected(std::size_t n)
    : points(3 * n), normals(3 * n), displacement(n), iterations(n), converged(n)
  {
  }
  gls::ProjectionOutputs outputs()
  {
    return { points.data(), normals.data(), displacement.data(), iterations.data(), converged.data() };
  }
};

Projected project(const glstest::Cloud& c, const std::vector<double>& scales, int threads = 0)
{
  Projected r(c.size());
  gls::ProjectionSettings settings;
  settings.parallel.threads = threads;
  EXPECT_TRUE(gls::projectPointCloud(c.points.data(), c.normals.data(), c.size(), scales.data(), settings,
    r.outputs()));
  return r;
}

} // namespace

TEST(Projection, OneStepLandsOnTheFittedSphereAndPlane)
{
  // A sample as the fit reports it for the sphere |x - c| = R seen from the origin: tau = |c| - R... with c = (0,0,-D)
  // and outward normals, the origin is at distance D - R outside the sphere along +z.
  for (double R : { 0.5, 2.0, 1e6 })
  {
    const double D = R + 0.1;
    gls::ScaleSample s{};
    const double kappa = 1.0 / R;
    // s(x) = (|x - c|^2 - R^2) / (2R): s(0) = (D^2 - R^2)/(2R), gradient (0,0,D/R), kappa = 1/R.
    s.tau = (D * D - R * R) / (2.0 * R);
    s.kappa = kappa;
    s.eta = { 0.0, 0.0, 1.0 };
    s.valid = true;
    const gls::Vec3 q = gls::sphereProjectionOffset(s);
    EXPECT_NEAR(q.z, -(D - R), 1e-12 * D);
    EXPECT_EQ(q.x, 0.0);
  }
  gls::ScaleSample plane{};
  plane.tau = 0.25;
  plane.kappa = 0.0;
  plane.eta = { 0.0, 1.0, 0.0 };
  plane.valid = true;
  EXPECT_DOUBLE_EQ(gls::sphereProjectionOffset(plane).y, -0.25);
}

TEST(Projection, OffSurfacePointsProjectOntoAnExactSphere)
{
  const double R = 2.0;
  const glstest::Cloud c = glstest::sphere(4000, R);
  gls::NeighborGrid grid;
  grid.build(c.points.data(), c.normals.data(), c.size(), 0.4);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 50; ++i)
  {
    gls::Vec3 d{ u(rng), u(rng), u(rng) };
    d = (1.0 / std::sqrt(gls::squaredNorm(d))) * d;
    const gls::Vec3 p = (R + 0.2 * u(rng)) * d;
    const gls::ProjectionResult r = gls::projectOntoSurface(grid.view(), p, 0.8, 6.0, 50, 1e-10);
    ASSERT_TRUE(r.valid);
    EXPECT_TRUE(r.converged);
    EXPECT_NEAR(std::sqrt(gls::squaredNorm(r.position)), R, 1e-9);
    EXPECT_NEAR(gls::dot(r.normal, d), 1.0, 1e-9);
    EXPECT_NEAR(gls::dot((1.0 / R) * r.position, d), 1.0, 1e-9); // radial: no drift along the surface
  }
}

TEST(Projection, DenoisesANoisyPlaneAndKeepsTheSamplesOfACleanSphere)
{
  // Noisy plane: z noise of 0.01 with exact normals; after projection at t = 0.3 the residual z is far smaller.
  glstest::Cloud c = glstest::plane(60, 2.0);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0.0, 0.01);
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    c.points[3 * i + 2] = g(rng);
  }
  const Projected p = project(c, std::vector<double>(c.size(), 0.3));
  double before = 0.0, after = 0.0;
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    before += c.points[3 * i + 2] * c.points[3 * i + 2];
    after += p.points[3 * i + 2] * p.points[3 * i + 2];
    EXPECT_EQ(p.converged[i], 1);
  }
  EXPECT_LT(std::sqrt(after / before), 0.25);

  // Clean sphere samples are fixed points: they move by (almost) nothing.
  const glstest::Cloud s = glstest::sphere(3000, 1.0);
  const Projected q = project(s, std::vector<double>(s.size(), 0.3));
  for (std::size_t i = 0; i < s.size(); ++i)
  {
    EXPECT_LT(q.displacement[i], 1e-9);
  }
}

TEST(Projection, BadPointsKeepTheirPositionAndEveryOtherResultIsUnchanged)
{
  glstest::Cloud c = glstest::sphere(2000, 1.0);
  std::vector<double> scales(c.size(), 0.3);
  const Projected clean = project(c, scales);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  glstest::Cloud bad = c;
  bad.add(nan, 0.0, 0.0, 0.0, 0.0, 1.0);  // non-finite coordinates
  bad.add(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);  // zero normal: left out of every neighbourhood
  bad.add(50.0, 0.0, 0.0, 1.0, 0.0, 0.0); // isolated: too few neighbours
  scales.insert(scales.end(), { 0.3, 0.3, 0.3 });
  scales[0] = -1.0; // an invalid scale: the point is not projected
  const Projected r = project(bad, scales);
  for (std::size_t i = 1; i < c.size(); ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      // The isolated point widens the grid, which changes the order of the sums: equal up to rounding.
      EXPECT_NEAR(r.points[3 * i + a], clean.points[3 * i + a], 1e-13);
    }
  }
  EXPECT_TRUE(std::isnan(r.displacement[0]));
  EXPECT_EQ(r.points[0], c.points[0]);
  const std::size_t n = c.size();
  EXPECT_TRUE(std::isnan(r.displacement[n]));
  EXPECT_TRUE(std::isnan(r.points[3 * n]));
  EXPECT_FALSE(std::isnan(r.displacement[n + 1])); // its own fit uses the others
  EXPECT_TRUE(std::isnan(r.displacement[n + 2]));
  EXPECT_EQ(r.points[3 * (n + 2)], 50.0);
  EXPECT_EQ(r.converged[n + 2], 0);
}

TEST(Projection, BitwiseIdenticalForAnyThreadCount)
{
  const glstest::Cloud c = glstest::paraboloid(80, 1.0, 0.5, -0.3, 0.01, 0.05, 11);
  std::vector<double> scales(c.size());
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    scales[i] = 0.15 + 0.1 * static_cast<double>(i % 7) / 7.0;
  }
  const Projected one = project(c, scales, 1);
  for (int threads : { 2, 3, 8 })
  {
    const Projected many = project(c, scales, threads);
    EXPECT_EQ(one.points, many.points);
    EXPECT_EQ(one.normals, many.normals);
    EXPECT_EQ(one.iterations, many.iterations);
  }
}

TEST(AdaptiveBandwidth, RawBandwidthScansCoarseToFine)
{
  const std::vector<double> t = { 0.1, 0.2, 0.4, 0.8, 1.6 };
  const double ln2 = std::log(2.0);
  // Flat nu: nothing to smooth, the smallest scale.
  const std::vector<double> flat = { 0.001, 0.001, 0.001, 0.001, 0.001 };
  EXPECT_EQ(gls::rawBandwidth(flat.data(), t.data(), 5, 0.01), 0.1);
  // Noise below 0.4: nu rises by 0.5 from t = 0.4 to 0.2 (slope 0.5 / ln 2 > 0.01): bandwidth 0.4.
  const std::vector<double> noisy = { 0.9, 0.5, 0.0, 0.0, 0.0 };
  EXPECT_EQ(gls::rawBandwidth(noisy.data(), t.data(), 5, 0.01), 0.4);
  // The threshold is on the slope in ln t: a rise of 0.02 ln 2 passes 0.01 but not 0.03.
  const std::vector<double> gentle = { 0.02 * ln2, 0.0, 0.0, 0.0, 0.0 };
  EXPECT_EQ(gls::rawBandwidth(gentle.data(), t.data(), 5, 0.01), 0.2);
  EXPECT_EQ(gls::rawBandwidth(gentle.data(), t.data(), 5, 0.03), 0.1);
  // nu falling towards fine scales (a feature leaving the ball) does not stop the scan.
  const std::vector<double> falling = { 0.0, 0.0, 0.1, 0.5, 0.9 };
  EXPECT_EQ(gls::rawBandwidth(falling.data(), t.data(), 5, 0.01), 0.1);
  // Undefined nu at fine scales (too few neighbours) stops it above them; at the coarsest scale: NaN.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> sparse = { nan, nan, 0.0, 0.0, 0.0 };
  EXPECT_EQ(gls::rawBandwidth(sparse.data(), t.data(), 5, 0.01), 0.4);
  const std::vector<double> none = { 0.0, 0.0, 0.0, 0.0, nan };
  EXPECT_TRUE(std::isnan(gls::rawBandwidth(none.data(), t.data(), 5, 0.01)));
}

TEST(AdaptiveBandwidth, SmoothingIsAWeightedMeanOverNeighbours)
{
  // Points on a line, spacing 1; raw = x. A radius of 2.5 sees 2 neighbours each side with weights symmetric
  // about the point, so the mean of a linear function is itself in the interior.
  const std::size_t n = 40;
  std::vector<double> xyz, raw;
  for (std::size_t i = 0; i < n; ++i)
  {
    xyz.insert(xyz.end(), { static_cast<double>(i), 0.0, 0.0 });
    raw.push_back(static_cast<double>(i));
  }
  raw[20] = std::numeric_limits<double>::quiet_NaN(); // filled from its neighbours
  xyz[3 * 30] = std::numeric_limits<double>::infinity();
  std::vector<double> out(n), copy(n);
  gls::ParallelOptions options;
  ASSERT_TRUE(gls::smoothBandwidth(xyz.data(), n, raw.data(), 2.5, options, out.data()));
  for (std::size_t i = 3; i < 27; ++i)
  {
    if (i < 18 || i > 22) // 18..22 see the gap at 20 on one side only
    {
      EXPECT_NEAR(out[i], static_cast<double>(i), 1e-12) << i;
    }
  }
  EXPECT_NEAR(out[20], 20.0, 1e-12); // symmetric neighbours fill the gap
  EXPECT_TRUE(std::isnan(out[30]));
  // At the end of the line the neighbours are one-sided: x = 0 sees 1 and 2 with weights w(1), w(2).
  const double w1 = std::pow(1.0 / 6.25 - 1.0, 2), w2 = std::pow(4.0 / 6.25 - 1.0, 2);
  EXPECT_NEAR(out[0], (w1 * 1.0 + w2 * 2.0) / (1.0 + w1 + w2), 1e-12);
  ASSERT_TRUE(gls::smoothBandwidth(xyz.data(), n, raw.data(), 0.0, options, copy.data()));
  EXPECT_EQ(copy[5], 5.0);
  EXPECT_TRUE(std::isnan(copy[20]));
}
