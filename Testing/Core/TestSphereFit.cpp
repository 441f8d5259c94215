// Analytic oracles of docs/math.md: spheres (outward, inward, off-surface evaluation), planes, the complement
// property, 2D circle and sinusoid, rigid-motion and scaling invariance, degenerate neighbourhoods.
#include "CollectingSink.h"
#include "TestClouds.h"

#include "gls/Descriptors.h"
#include "gls/ScaleSampling.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace glstest;

namespace
{

const std::vector<double> kSphereScales = gls::sampleScales(0.15, 0.9, 8, gls::ScaleSampling::Quadratic);

} // namespace

TEST(SphereFit, OutwardSphereGivesExactCurvatureAndZeroVariation)
{
  const double r = 0.7;
  const Cloud c = sphere(4000, r);
  const CollectingSink s = runScaleSpace(c.points, c.normals, kSphereScales);
  for (std::size_t i = 0; i < c.size(); i += 37)
  {
    for (std::size_t k = 0; k < kSphereScales.size(); ++k)
    {
      const gls::ScaleSample& f = s.at(i, k);
      ASSERT_TRUE(f.valid) << i << " " << k;
      EXPECT_NEAR(f.tau, 0.0, 1e-10);
      EXPECT_NEAR(f.kappa, 1.0 / r, 1e-9);
      EXPECT_NEAR(f.phi, 1.0, 1e-9);
      EXPECT_NEAR(f.dtau, 0.0, 1e-8);
      EXPECT_NEAR(f.dkappa, 0.0, 1e-7);
      EXPECT_NEAR(std::sqrt(gls::squaredNorm(f.deta)), 0.0, 1e-8);
      EXPECT_NEAR(gls::dot(f.eta, gls::Vec3{ c.normals[3 * i], c.normals[3 * i + 1], c.normals[3 * i + 2] }), 1.0,
        1e-10);
      EXPECT_NEAR(gls::geometricVariation(f, kSphereScales[k], {}), 0.0, 1e-12);
    }
  }
}

TEST(SphereFit, InwardSphereGivesNegativeCurvature)
{
  const double r = 2.5;
  const Cloud c = sphere(4000, r, true);
  const std::vector<double> scales = gls::sampleScales(0.5, 3.0, 5, gls::ScaleSampling::Linear);
  const CollectingSink s = runScaleSpace(c.points, c.normals, scales);
  for (std::size_t i = 0; i < c.size(); i += 101)
  {
    for (std::size_t k = 0; k < scales.size(); ++k)
    {
      ASSERT_TRUE(s.at(i, k).valid);
      EXPECT_NEAR(s.at(i, k).kappa, -1.0 / r, 1e-9);
      EXPECT_NEAR(s.at(i, k).phi, 1.0, 1e-9);
    }
  }
}

TEST(SphereFit, OffSurfacePositionGetsAlgebraicDistance)
{
  // With phi = 1 the normalized field is s(x) = (|x - c|^2 - r^2) / (2 r), so tau(p) = (D^2 - r^2) / (2 r).
  const double r = 1.0;
  const Cloud c = sphere(6000, r);
  gls::ScaleSpaceSettings settings;
  settings.scales = { 0.4, 0.8, 1.5 };
  gls::ScaleSpaceEngine engine(c.points.data(), c.normals.data(), c.size(), settings);
  for (double D : { 1.05, 0.9, 1.2 })
  {
    std::vector<gls::ScaleSample> out;
    engine.evaluatePosition({ 0.0, 0.0, D }, out);
    for (const gls::ScaleSample& f : out)
    {
      ASSERT_TRUE(f.valid);
      EXPECT_NEAR(f.tau, (D * D - r * r) / (2 * r), 1e-10);
      EXPECT_NEAR(f.kappa, 1.0 / r, 1e-9);
      EXPECT_NEAR(f.eta.z, 1.0, 1e-10);
    }
  }
}

TEST(SphereFit, PlaneGivesZeroCurvatureAndSignedDistance)
{
  const Cloud c = plane(60, 2.0);
  gls::ScaleSpaceSettings settings;
  settings.scales = { 0.1, 0.2, 0.4 };
  gls::ScaleSpaceEngine engine(c.points.data(), c.normals.data(), c.size(), settings);
  for (double h : { 0.0, 0.03, -0.05 })
  {
    std::vector<gls::ScaleSample> out;
    engine.evaluatePosition({ 0.11, -0.2, h }, out);
    for (std::size_t k = 0; k < out.size(); ++k)
    {
      ASSERT_TRUE(out[k].valid);
      EXPECT_NEAR(out[k].kappa, 0.0, 1e-10);
      EXPECT_NEAR(out[k].phi, 1.0, 1e-12);
      EXPECT_NEAR(out[k].tau, h, 1e-12);
      EXPECT_NEAR(out[k].eta.z, 1.0, 1e-12);
      EXPECT_NEAR(gls::geometricVariation(out[k], settings.scales[k], {}), 0.0, 1e-16);
    }
  }
}

TEST(SphereFit, NegatedNormalsNegateTauEtaKappaAndKeepPhi)
{
  const Cloud c = paraboloid(40, 1.0, 0.6, -0.3, 0.01, 0.05, 7);
  std::vector<double> flipped(c.normals);
  for (double& v : flipped)
  {
    v = -v;
  }
  const std::vector<double> scales = gls::sampleScales(0.15, 0.6, 6, gls::ScaleSampling::Quadratic);
  const CollectingSink a = runScaleSpace(c.points, c.normals, scales);
  const CollectingSink b = runScaleSpace(c.points, flipped, scales);
  int compared = 0;
  for (std::size_t i = 0; i < c.size(); i += 13)
  {
    for (std::size_t k = 0; k < scales.size(); ++k)
    {
      const gls::ScaleSample& p = a.at(i, k);
      const gls::ScaleSample& q = b.at(i, k);
      ASSERT_EQ(p.valid, q.valid);
      if (!p.valid)
      {
        continue;
      }
      ++compared;
      EXPECT_NEAR(p.tau, -q.tau, 1e-12);
      EXPECT_NEAR(p.kappa, -q.kappa, 1e-9);
      EXPECT_NEAR(p.phi, q.phi, 1e-12);
      EXPECT_NEAR(p.eta.x, -q.eta.x, 1e-12);
      EXPECT_NEAR(p.dtau, -q.dtau, 1e-9);
      EXPECT_NEAR(p.dkappa, -q.dkappa, 1e-6);
      EXPECT_NEAR(gls::geometricVariation(p, scales[k], {}), gls::geometricVariation(q, scales[k], {}), 1e-9);
    }
  }
  EXPECT_GT(compared, 500);
}

TEST(SphereFit, CircleIn2DReducesToTheCircleFit)
{
  const double r = 0.5;
  const Cloud c = circle2D(400, r);
  const std::vector<double> scales = { 0.05, 0.2, 0.6 };
  const CollectingSink s = runScaleSpace(c.points, c.normals, scales, 0, 3.0);
  for (std::size_t i = 0; i < c.size(); i += 7)
  {
    for (std::size_t k = 0; k < scales.size(); ++k)
    {
      const gls::ScaleSample& f = s.at(i, k);
      ASSERT_TRUE(f.valid);
      EXPECT_NEAR(f.kappa, 1.0 / r, 1e-9);
      EXPECT_NEAR(f.phi, 1.0, 1e-9);
      EXPECT_NEAR(f.eta.z, 0.0, 1e-14);
      EXPECT_NEAR(gls::geometricVariation(f, scales[k], {}), 0.0, 1e-12);
    }
  }
}

TEST(SphereFit, SinusoidCurvatureAtTheCrestConvergesAtSmallScales)
{
  // y = A sin(w x): curvature at the crest x = pi / (2 w) is A w^2 (1/radius of the osculating circle).
  const double A = 0.2, w = 3.0;
  const Cloud c = sinusoid2D(20001, A, w, -2.0, 3.0);
  const double crest = M_PI / (2 * w);
  const std::vector<double> scales = { 0.01, 0.02, 0.04, 0.3 };
  gls::ScaleSpaceSettings settings;
  settings.scales = scales;
  settings.minNeighbors = 3;
  gls::ScaleSpaceEngine engine(c.points.data(), c.normals.data(), c.size(), settings);
  std::vector<gls::ScaleSample> out;
  engine.evaluatePosition({ crest, A, 0.0 }, out);
  const double exact = A * w * w;
  EXPECT_NEAR(out[0].kappa, exact, 1e-3 * exact);
  EXPECT_NEAR(out[1].kappa, exact, 4e-3 * exact);
  EXPECT_NEAR(out[2].kappa, exact, 1.6e-2 * exact);
  // The error grows with the scale (O(t^2)), and the large scale sees the neighbouring troughs.
  EXPECT_LT(std::abs(out[0].kappa - exact), std::abs(out[2].kappa - exact));
  EXPECT_GT(std::abs(out[3].kappa - exact), 0.05 * exact);
  EXPECT_NEAR(out[0].tau, 0.0, 1e-6);
  EXPECT_GT(gls::geometricVariation(out[3], scales[3], {}), 1e-4);
}

TEST(SphereFit, RigidMotionAndUniformScalingLeaveDimensionlessDescriptorsUnchanged)
{
  const Cloud c = paraboloid(35, 1.0, 0.8, 0.2, 0.01, 0.03, 11);
  const std::vector<double> scales = gls::sampleScales(0.2, 0.7, 5, gls::ScaleSampling::Logarithmic);
  // Rotation about (1, 2, 2)/3 by 0.7 rad, scaling by 3.5, translation by (10, -4, 2).
  const double ax = 1 / 3.0, ay = 2 / 3.0, az = 2 / 3.0, th = 0.7, sc = 3.5;
  const double C = std::cos(th), S = std::sin(th), V = 1 - C;
  const double R[3][3] = { { C + ax * ax * V, ax * ay * V - az * S, ax * az * V + ay * S },
    { ay * ax * V + az * S, C + ay * ay * V, ay * az * V - ax * S },
    { az * ax * V - ay * S, az * ay * V + ax * S, C + az * az * V } };
  auto rotate = [&](const double* v, double* o) {
    for (int r = 0; r < 3; ++r)
    {
      o[r] = R[r][0] * v[0] + R[r][1] * v[1] + R[r][2] * v[2];
    }
  };
  Cloud m;
  m.points.resize(c.points.size());
  m.normals.resize(c.normals.size());
  const double shift[3] = { 10, -4, 2 };
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    rotate(&c.points[3 * i], &m.points[3 * i]);
    rotate(&c.normals[3 * i], &m.normals[3 * i]);
    for (int a = 0; a < 3; ++a)
    {
      m.points[3 * i + a] = sc * m.points[3 * i + a] + shift[a];
    }
  }
  std::vector<double> scaled(scales);
  for (double& t : scaled)
  {
    t *= sc;
  }
  const CollectingSink a = runScaleSpace(c.points, c.normals, scales);
  const CollectingSink b = runScaleSpace(m.points, m.normals, scaled);
  int compared = 0;
  for (std::size_t i = 0; i < c.size(); i += 11)
  {
    for (std::size_t k = 0; k < scales.size(); ++k)
    {
      const gls::ScaleSample& p = a.at(i, k);
      const gls::ScaleSample& q = b.at(i, k);
      ASSERT_EQ(p.valid, q.valid);
      if (!p.valid)
      {
        continue;
      }
      ++compared;
      EXPECT_NEAR(p.tau / scales[k], q.tau / scaled[k], 1e-9);
      EXPECT_NEAR(p.kappa * scales[k], q.kappa * scaled[k], 1e-9);
      EXPECT_NEAR(p.phi, q.phi, 1e-9);
      EXPECT_NEAR(p.dtau, q.dtau, 1e-8);
      const double eta[3] = { p.eta.x, p.eta.y, p.eta.z };
      double rotated[3];
      rotate(eta, rotated);
      EXPECT_NEAR(rotated[0], q.eta.x, 1e-9);
      EXPECT_NEAR(rotated[1], q.eta.y, 1e-9);
      EXPECT_NEAR(rotated[2], q.eta.z, 1e-9);
      EXPECT_NEAR(
        gls::geometricVariation(p, scales[k], {}), gls::geometricVariation(q, scaled[k], {}), 1e-8);
    }
  }
  EXPECT_GT(compared, 400);
}

TEST(SphereFit, DegenerateNeighbourhoodsGiveNaNNeverZero)
{
  // Too few neighbours: NaN at the small scale, valid at the large one.
  const Cloud c = sphere(200, 1.0);
  const CollectingSink s = runScaleSpace(c.points, c.normals, { 1e-4, 1.0 });
  EXPECT_FALSE(s.at(0, 0).valid);
  EXPECT_TRUE(std::isnan(s.at(0, 0).kappa));
  EXPECT_TRUE(std::isnan(s.at(0, 0).tau));
  EXPECT_EQ(s.at(0, 0).neighbors, 1.0);
  EXPECT_TRUE(s.at(0, 1).valid);

  // All neighbours at one place: the plane through them, kappa 0 (not NaN), tau 0, eta the mean normal.
  Cloud same;
  for (int i = 0; i < 50; ++i)
  {
    same.add(1.0, 2.0, 3.0, 0.0, 0.0, 1.0);
  }
  const CollectingSink d = runScaleSpace(same.points, same.normals, { 0.5 });
  ASSERT_TRUE(d.at(10, 0).valid);
  EXPECT_EQ(d.at(10, 0).kappa, 0.0);
  EXPECT_EQ(d.at(10, 0).tau, 0.0);
  EXPECT_EQ(d.at(10, 0).eta.z, 1.0);

  // Same place, normals cancelling: undefined gradient, NaN.
  Cloud cancel;
  for (int i = 0; i < 50; ++i)
  {
    cancel.add(0.0, 0.0, 0.0, 0.0, 0.0, i % 2 ? 1.0 : -1.0);
  }
  const CollectingSink e = runScaleSpace(cancel.points, cancel.normals, { 0.5 });
  EXPECT_FALSE(e.at(3, 0).valid);
  EXPECT_TRUE(std::isnan(e.at(3, 0).phi));
}

TEST(SphereFit, NonFiniteAndZeroNormalPointsStayOutOfNeighbourhoods)
{
  const Cloud c = paraboloid(30, 1.0, 0.5, 0.5, 0.0, 0.0, 3);
  Cloud polluted = c;
  const double nan = std::nan("");
  polluted.add(0.0, 0.0, 0.01, 0.0, 0.0, 0.0);   // zero normal
  polluted.add(nan, 0.0, 0.0, 0.0, 0.0, 1.0);    // NaN position
  polluted.add(0.01, 0.0, 0.0, nan, 0.0, 1.0);   // NaN normal
  // A non-unit normal is normalized: scale one normal by 5.
  for (int a = 0; a < 3; ++a)
  {
    polluted.normals[3 * 17 + a] *= 5.0;
  }
  const std::vector<double> scales = { 0.2, 0.5 };
  const CollectingSink a = runScaleSpace(c.points, c.normals, scales);
  const CollectingSink b = runScaleSpace(polluted.points, polluted.normals, scales);
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    for (std::size_t k = 0; k < scales.size(); ++k)
    {
      ASSERT_EQ(a.at(i, k).valid, b.at(i, k).valid);
      if (!a.at(i, k).valid)
      {
        continue;
      }
      EXPECT_NEAR(a.at(i, k).kappa, b.at(i, k).kappa, 1e-12 * (1 + std::abs(a.at(i, k).kappa)));
      EXPECT_NEAR(a.at(i, k).tau, b.at(i, k).tau, 1e-14);
    }
  }
  EXPECT_FALSE(b.at(c.size() + 1, 0).valid); // NaN position: NaN results
  EXPECT_TRUE(b.at(c.size(), 1).valid);      // zero normal: still evaluated from its neighbours
}
