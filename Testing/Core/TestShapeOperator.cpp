// Principal curvatures and directions at every scale (ShapeOperator.h), against three oracles: analytic surfaces with
// exact normals (their curvatures from the fundamental forms of the parametrization), central differences of the
// fitted normal eta over positions, and kappa on a sphere. Run through the host/device loop, its windowed form (the
// CUDA kernel's loop) and the CPU kernel's two builds.
#include "AnalyticSurfaces.h"
#include "TestBinning.h"
#include "TestGrid.h"
#include "TestClouds.h"

#include "OnePassKernelBody.h" // the CPU kernels for any moment set (private to the core)
#include "multiresolution/MultiresolutionKernelBody.h"

#include "gls/MultiresolutionCellSums.h"
#include "gls/MultiresolutionReferenceWalk.h"
#include "gls/NeighborGrid.h"
#include "gls/PointScaleSpace.h"
#include "gls/ScaleSpaceEngine.h"
#include "gls/ShapeOperator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

using namespace glstest;

namespace
{

/// What a shape's check measured.
struct Accuracy
{
  double curvatureP99 = 0.0; ///< p99 of |k - k_true| / max |k_true|
  double directionP99 = 0.0; ///< p99 of d1's angle to the true one, degrees, where |k1 - k2| >= 0.2 max |k|
  long curvatures = 0, directions = 0;
};


/// Evaluates the points of the patch within `reach` of its site (u0, v0) at the scales (fractions of the smallest
/// radius of curvature over those points, at most 5%) with the host/device loop, and compares with the truth.
Accuracy measure(const Surface& s, double u0, double v0, double du, double dv, const std::vector<double>& fractions,
  double smallestRadius, unsigned seed)
{
  std::vector<double> scales;
  for (double f : fractions)
  {
    scales.push_back(f * smallestRadius);
  }
  const double t = scales.back();
  const double density = 1000.0 / (kPi * scales.front() * scales.front()); // 1000 points in the smallest ball
  const Patch patch = samplePatch(s, u0, v0, du, dv, density, seed);
  gls::NeighborGrid grid;
  grid.build(patch.cloud.points.data(), patch.cloud.normals.data(), patch.cloud.size(), t / 4.0);
  const TestBinning binning(scales);
  const std::size_t S = scales.size();
  std::vector<gls::MomentsT<gls::ShapeOperatorMoments>> bins(S);
  std::vector<gls::CurvatureSample> out(S);
  CurvatureErrors errors;
  const gls::Vec3 site = s.X(u0, v0);
  for (std::size_t i = 0; i < patch.cloud.size(); i += 7)
  {
    const gls::Vec3 p{ patch.cloud.points[3 * i], patch.cloud.points[3 * i + 1], patch.cloud.points[3 * i + 2] };
    if (gls::squaredNorm(p - site) > t * t)
    {
      continue;
    }
    gls::evaluateAllScales<gls::ShapeOperatorMoments>(grid.view(), p, binning.View, 6.0, bins.data(), out.data());
    const gls::PrincipalCurvatures want = truth(s, patch.u[i], patch.v[i]);
    for (std::size_t k = 0; k < S; ++k)
    {
      const gls::PrincipalCurvatures& got = out[k].principal;
      EXPECT_TRUE(out[k].sphere.valid) << s.name;
      if (errors.add(got, want))
      {
        // The frame: unit, tangent to the fitted normal, d1 x d2 = eta.
        EXPECT_NEAR(gls::squaredNorm(got.d1), 1.0, 1e-12);
        EXPECT_NEAR(gls::dot(got.d1, out[k].sphere.eta), 0.0, 1e-12);
        const gls::Vec3 e = gls::cross(got.d1, got.d2) - out[k].sphere.eta;
        EXPECT_LT(gls::squaredNorm(e), 1e-24);
      }
    }
  }
  Accuracy a;
  a.curvatureP99 = percentile99(errors.curvature);
  a.directionP99 = percentile99(errors.direction);
  a.curvatures = static_cast<long>(errors.curvature.size());
  a.directions = static_cast<long>(errors.direction.size());
  return a;
}

void expectAccurate(const Surface& s, double u0, double v0, double du, double dv, double smallestRadius,
  bool expectDirections, unsigned seed)
{
  const Accuracy a = measure(s, u0, v0, du, dv, { 0.03, 0.04, 0.05 }, smallestRadius, seed);
  std::printf("%-9s at (%.2f, %.2f): p99 |k - k_true| / max|k| = %.3g%% (%ld), p99 direction error %.3g deg (%ld)\n",
    s.name.c_str(), u0, v0, 100.0 * a.curvatureP99, a.curvatures, a.directionP99, a.directions);
  EXPECT_GT(a.curvatures, 30) << s.name;
  EXPECT_LE(a.curvatureP99, 0.01) << s.name << " at " << u0 << ", " << v0;
  if (expectDirections)
  {
    EXPECT_GT(a.directions, 30) << s.name;
    EXPECT_LE(a.directionP99, 2.0) << s.name << " at " << u0 << ", " << v0;
  }
}

} // namespace

TEST(ShapeOperator, SphereCurvaturesAreKappaAndDirectionsUndefined)
{
  // On a sphere the fit is the sphere at any p: D u_l = 2 u_q I, so k1 = k2 = kappa = 1/R (to rounding), H = kappa,
  // K = 1/R^2, shape index 1, curvedness 1/R, and the directions are NaN (an umbilic).
  const double R = 0.8;
  const Surface s = sphere(R);
  const std::vector<double> scales{ 0.02, 0.04 };
  const Patch patch = samplePatch(s, 0.0, 0.3, 0.15, 0.15, 400.0 / (kPi * 0.02 * 0.02), 3);
  gls::NeighborGrid grid;
  grid.build(patch.cloud.points.data(), patch.cloud.normals.data(), patch.cloud.size(), 0.01);
  const TestBinning binning(scales);
  std::vector<gls::MomentsT<gls::ShapeOperatorMoments>> bins(2);
  std::vector<gls::CurvatureSample> out(2);
  long checked = 0;
  for (std::size_t i = 0; i < patch.cloud.size(); i += 53)
  {
    const gls::Vec3 p{ patch.cloud.points[3 * i], patch.cloud.points[3 * i + 1], patch.cloud.points[3 * i + 2] };
    if (gls::squaredNorm(p - s.X(0.0, 0.3)) > 0.05 * 0.05)
    {
      continue;
    }
    gls::evaluateAllScales<gls::ShapeOperatorMoments>(grid.view(), p, binning.View, 6.0, bins.data(), out.data());
    for (const gls::CurvatureSample& c : out)
    {
      ASSERT_TRUE(c.sphere.valid);
      EXPECT_NEAR(c.sphere.kappa, 1.0 / R, 1e-9);
      EXPECT_NEAR(c.principal.k1, c.sphere.kappa, 1e-9 * c.sphere.kappa);
      EXPECT_NEAR(c.principal.k2, c.sphere.kappa, 1e-9 * c.sphere.kappa);
      EXPECT_NEAR(gls::meanCurvature(c.principal), c.sphere.kappa, 1e-9 * c.sphere.kappa);
      EXPECT_NEAR(gls::gaussianCurvature(c.principal), 1.0 / (R * R), 1e-8 / (R * R));
      EXPECT_NEAR(gls::shapeIndex(c.principal, 0.02), 1.0, 1e-9);
      EXPECT_NEAR(gls::curvedness(c.principal), 1.0 / R, 1e-9 / R);
      EXPECT_TRUE(std::isnan(c.principal.d1.x) && std::isnan(c.principal.d2.z));
      ++checked;
    }
  }
  EXPECT_GT(checked, 20);
}

TEST(ShapeOperator, AnalyticSurfacesWithinOnePercentAndTwoDegrees)
{
  // Scales 2%, 3.5% and 5% of the smallest radius of curvature of the evaluated region; 400 points in the smallest
  // ball. The bounds: p99 of |k - k_true| / max|k_true| <= 1%, directions p99 <= 2 degrees where
  // |k1 - k2| >= 0.2 max |k|.
  expectAccurate(sphere(1.0), 0.3, 0.4, 0.12, 0.12, 1.0, false, 11);
  expectAccurate(cylinder(0.5), 0.0, 0.0, 0.12, 0.06, 0.5, true, 12);
  const double R = 1.0, r = 0.4;
  // Outer equator (k = 1/r, 1/(R + r)), top (1/r, 0), inner equator (1/r, -1/(R - r)) and between.
  expectAccurate(torus(R, r), 0.0, 0.0, 0.05, 0.12, r, true, 13);
  expectAccurate(torus(R, r), 0.5, 0.5 * kPi, 0.05, 0.12, r, true, 14);
  expectAccurate(torus(R, r), 1.0, kPi, 0.08, 0.12, r, true, 15);
  expectAccurate(torus(R, r), 2.0, 2.2, 0.08, 0.12, r, true, 16);
  // Ellipsoid (1, 0.7, 0.5): smallest radius of curvature c^2 / a = 0.25 (at (a, 0, 0)).
  expectAccurate(ellipsoid(1.0, 0.7, 0.5), 0.0, 0.0, 0.06, 0.12, 0.25, true, 17);
  expectAccurate(ellipsoid(1.0, 0.7, 0.5), 0.9, 0.5, 0.06, 0.06, 0.25, true, 18);
  expectAccurate(ellipsoid(1.0, 0.7, 0.5), 2.5, 1.1, 0.12, 0.06, 0.25, true, 19);
  // The saddle z = (x^2 - y^2) / 2 at its centre: k = 1 (along y) and -1 (along x).
  expectAccurate(saddle(), 0.0, 0.0, 0.1, 0.1, 1.0, true, 20);
}

TEST(ShapeOperator, IsTheDerivativeOfTheFittedNormalOverPositions)
{
  // Central differences of the oriented sphere's eta over the evaluation point (step 1e-5 t), scaled as the shape
  // operator is (by |u_l| / sqrt(phi) = sqrt(1 + 2 tau kappa): the curvature of the fitted surface, not of the level
  // set through p), in the same tangent basis and symmetrized: the same k1 and k2, on a noisy cloud.
  const Cloud c = paraboloid(90, 1.0, 0.9, -0.4, 0.01, 0.05, 7);
  const std::vector<double> scales{ 0.15, 0.3 };
  gls::NeighborGrid grid;
  grid.build(c.points.data(), c.normals.data(), c.size(), 0.075);
  const TestBinning binning(scales);
  std::vector<gls::MomentsT<gls::ShapeOperatorMoments>> bins(2);
  std::vector<gls::Moments> sphereBins(2);
  std::vector<gls::CurvatureSample> out(2);
  std::vector<gls::ScaleSample> plus(2), minus(2);
  double worst = 0.0;
  long checked = 0;
  for (std::size_t i = 0; i < c.size(); i += 97)
  {
    const gls::Vec3 p{ c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2] };
    if (std::abs(p.x) > 0.6 || std::abs(p.y) > 0.6)
    {
      continue;
    }
    gls::evaluateAllScales<gls::ShapeOperatorMoments>(grid.view(), p, binning.View, 6.0, bins.data(), out.data());
    for (std::size_t k = 0; k < scales.size(); ++k)
    {
      const double t = scales[k], h = 1e-5 * t;
      gls::Vec3 column[3];
      for (int j = 0; j < 3; ++j)
      {
        const gls::Vec3 e{ j == 0 ? h : 0.0, j == 1 ? h : 0.0, j == 2 ? h : 0.0 };
        gls::evaluateAllScales(grid.view(), p + e, binning.View, 6.0, sphereBins.data(), plus.data());
        gls::evaluateAllScales(grid.view(), p - e, binning.View, 6.0, sphereBins.data(), minus.data());
        column[j] = (0.5 / h) * (plus[k].eta - minus[k].eta);
      }
      const gls::ScaleSample& s = out[k].sphere;
      ASSERT_TRUE(s.valid);
      const double scale = std::sqrt(1.0 + 2.0 * s.tau * s.kappa);
      const gls::Vec3 b1 = gls::orthogonalUnit(s.eta), b2 = gls::cross(s.eta, b1);
      const gls::Vec3 Sb1 = b1.x * column[0] + b1.y * column[1] + b1.z * column[2];
      const gls::Vec3 Sb2 = b2.x * column[0] + b2.y * column[1] + b2.z * column[2];
      const double a = scale * gls::dot(b1, Sb1), d = scale * gls::dot(b2, Sb2);
      const double b = 0.5 * scale * (gls::dot(b1, Sb2) + gls::dot(b2, Sb1));
      const gls::PrincipalCurvatures fd = gls::principalOf(a, b, d, b1, b2, s.eta, t);
      const gls::PrincipalCurvatures& got = out[k].principal;
      const double tolerance = 1e-6 * std::max({ std::abs(fd.k1), std::abs(fd.k2), 1.0 / t });
      EXPECT_NEAR(got.k1, fd.k1, tolerance) << "point " << i << " scale " << t;
      EXPECT_NEAR(got.k2, fd.k2, tolerance) << "point " << i << " scale " << t;
      EXPECT_LT(angleDegrees(got.d1, fd.d1), 1e-3);
      worst = std::max({ worst, std::abs(got.k1 - fd.k1) * t, std::abs(got.k2 - fd.k2) * t });
      ++checked;
    }
  }
  EXPECT_GT(checked, 40);
  std::printf("shape operator against central differences of eta: largest difference %.3g / t\n", worst);
}

TEST(ShapeOperator, PlaneIsFlatWithUndefinedDirectionsAndShapeIndex)
{
  const Cloud c = paraboloid(60, 1.0, 0.0, 0.0, 0.0, 0.0, 3);
  const std::vector<double> scales{ 0.2, 0.4 };
  gls::NeighborGrid grid;
  grid.build(c.points.data(), c.normals.data(), c.size(), 0.1);
  const TestBinning binning(scales);
  std::vector<gls::MomentsT<gls::ShapeOperatorMoments>> bins(2);
  std::vector<gls::CurvatureSample> out(2);
  for (std::size_t i = 0; i < c.size(); i += 131)
  {
    const gls::Vec3 p{ c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2] };
    gls::evaluateAllScales<gls::ShapeOperatorMoments>(grid.view(), p, binning.View, 6.0, bins.data(), out.data());
    for (std::size_t k = 0; k < scales.size(); ++k)
    {
      ASSERT_TRUE(out[k].sphere.valid);
      EXPECT_LT(std::abs(out[k].principal.k1) * scales[k], 1e-9);
      EXPECT_LT(std::abs(out[k].principal.k2) * scales[k], 1e-9);
      EXPECT_TRUE(std::isnan(out[k].principal.d1.x));
      EXPECT_TRUE(std::isnan(gls::shapeIndex(out[k].principal, scales[k])));
    }
  }
}

TEST(ShapeOperator, EveryKernelGivesTheSameCurvatures)
{
  // The windowed form (the CUDA kernel's loop) bit for bit the loop's; the CPU kernel's builds to rounding (the same
  // sums grouped otherwise).
  const Cloud c = paraboloid(70, 1.0, 0.8, 0.3, 0.005, 0.02, 5);
  const std::vector<double> scales{ 0.08, 0.12, 0.2, 0.3, 0.45 };
  gls::NeighborGrid grid;
  grid.build(c.points.data(), c.normals.data(), c.size(), 0.1);
  const TestBinning binning(scales);
  const std::size_t S = scales.size();
  std::vector<gls::MomentsT<gls::ShapeOperatorMoments>> bins(S);
  std::vector<gls::CurvatureSample> loop(S), windows(S), portable(S), fastest(S);
  double worst = 0.0;
  long checked = 0;
  for (std::size_t i = 0; i < c.size(); i += 41)
  {
    const gls::Vec3 p{ c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2] };
    gls::evaluateAllScales<gls::ShapeOperatorMoments>(grid.view(), p, binning.View, 6.0, bins.data(), loop.data());
    gls::evaluateAllScalesByWindows<4, gls::ShapeOperatorMoments>(grid.view(), p, binning.View, 6.0, windows.data());
    gls::onepass::evaluateAllScalesOnCpuFor<gls::ShapeOperatorMoments>(
      grid.view(), p, binning.View, 6.0, bins.data(), portable.data(), gls::CpuKernelBuild::Portable);
    gls::onepass::evaluateAllScalesOnCpuFor<gls::ShapeOperatorMoments>(
      grid.view(), p, binning.View, 6.0, bins.data(), fastest.data(), gls::CpuKernelBuild::Fastest);
    for (std::size_t k = 0; k < S; ++k)
    {
      const gls::PrincipalCurvatures& a = loop[k].principal;
      EXPECT_EQ(std::memcmp(&a, &windows[k].principal, sizeof a), 0) << "point " << i << " scale " << k;
      if (!loop[k].sphere.valid)
      {
        EXPECT_TRUE(std::isnan(portable[k].principal.k1) && std::isnan(fastest[k].principal.k1));
        continue;
      }
      for (const gls::CurvatureSample* other : { &portable[k], &fastest[k] })
      {
        worst = std::max({ worst, std::abs(other->principal.k1 - a.k1) * scales[k],
          std::abs(other->principal.k2 - a.k2) * scales[k] });
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 200);
  EXPECT_LT(worst, 1e-9);
  std::printf("CPU kernel against the loop: largest k t difference %.3g\n", worst);
}

namespace
{

/// Keeps each point's curvatures and checks that they come on the thread and just before its samples.
struct CurvatureRecorder : gls::ScaleSampleSink
{
  CurvatureRecorder(std::size_t points, std::size_t scales, int threads)
    : S(scales)
    , Curvatures(points * scales, gls::undefinedCurvatures())
    , Samples(points * scales)
    , Pending(static_cast<std::size_t>(threads), ~std::uint64_t(0))
  {
  }
  void consumeCurvatures(std::uint64_t id, const gls::PrincipalCurvatures* c, int thread) override
  {
    std::copy(c, c + this->S, &this->Curvatures[id * this->S]);
    this->Pending[static_cast<std::size_t>(thread)] = id;
    ++this->CurvatureCalls[thread];
  }
  void consume(std::uint64_t id, const gls::ScaleSample* s, int thread) override
  {
    std::copy(s, s + this->S, &this->Samples[id * this->S]);
    this->OutOfStep[thread] += this->Pending[static_cast<std::size_t>(thread)] == id ? 0 : 1;
    ++this->SampleCalls[thread];
  }
  long total(const long* counts) const { return counts[0] + counts[1] + counts[2] + counts[3]; }
  std::size_t S;
  std::vector<gls::PrincipalCurvatures> Curvatures;
  std::vector<gls::ScaleSample> Samples;
  std::vector<std::uint64_t> Pending;
  long CurvatureCalls[4] = {}, SampleCalls[4] = {}, OutOfStep[4] = {};
};

} // namespace

TEST(ShapeOperator, EngineFeedsCurvaturesBeforeEachPointsSamples)
{
  // An engine asked for the principal curvatures feeds them to consumeCurvatures just before each point's samples
  // (on the CPU, also when CUDA is asked for, saying why); they are the host/device loop's to rounding. A
  // multi-resolution engine feeds its own, the exact ones' to its accuracy; an engine not asked feeds none.
  const Patch patch = samplePatch(cylinder(0.5), 0.0, 0.0, 0.1, 0.05, 300.0 / (kPi * 0.012 * 0.012), 21);
  const Cloud& c = patch.cloud;
  const std::vector<double> scales{ 0.012, 0.02, 0.025 };
  const std::size_t S = scales.size(), n = c.size();
  gls::ScaleSpaceSettings settings;
  settings.scales = scales;
  settings.parallel.threads = 4;
  settings.principalCurvatures = true;
  settings.backend = gls::Backend::CUDA;
  const gls::ScaleSpaceEngine engine(c.points.data(), c.normals.data(), n, settings);
  CurvatureRecorder recorder(n, S, 4);
  gls::RunReport report;
  ASSERT_TRUE(engine.run(recorder, nullptr, nullptr, &report));
  EXPECT_EQ(report.used, gls::Backend::CPU);
  EXPECT_EQ(report.fallbackReason, "the principal curvatures are computed on the CPU only");
  EXPECT_EQ(recorder.total(recorder.CurvatureCalls), static_cast<long>(n));
  EXPECT_EQ(recorder.total(recorder.SampleCalls), static_cast<long>(n));
  EXPECT_EQ(recorder.total(recorder.OutOfStep), 0);
  gls::NeighborGrid grid;
  grid.build(c.points.data(), c.normals.data(), n, scales.back() / 4.0);
  const TestBinning binning(scales);
  std::vector<gls::MomentsT<gls::ShapeOperatorMoments>> bins(S);
  std::vector<gls::CurvatureSample> out(S);
  long checked = 0;
  for (std::size_t i = 0; i < n; i += 37)
  {
    const gls::Vec3 p{ c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2] };
    gls::evaluateAllScales<gls::ShapeOperatorMoments>(grid.view(), p, binning.View, 6.0, bins.data(), out.data());
    for (std::size_t k = 0; k < S; ++k)
    {
      const gls::PrincipalCurvatures& got = recorder.Curvatures[i * S + k];
      EXPECT_EQ(recorder.Samples[i * S + k].valid, out[k].sphere.valid);
      if (!out[k].sphere.valid)
      {
        EXPECT_TRUE(std::isnan(got.k1));
        continue;
      }
      EXPECT_NEAR(got.k1 * scales[k], out[k].principal.k1 * scales[k], 1e-10) << "point " << i;
      EXPECT_NEAR(got.k2 * scales[k], out[k].principal.k2 * scales[k], 1e-10) << "point " << i;
      EXPECT_NEAR(recorder.Samples[i * S + k].kappa * scales[k], out[k].sphere.kappa * scales[k], 1e-10);
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);

  // The multi-resolution engine: its curvatures from the curvature set's own cells, the exact ones' to its accuracy.
  settings.evaluation = gls::Evaluation::Multiresolution;
  const gls::ScaleSpaceEngine pyramid(c.points.data(), c.normals.data(), n, settings);
  CurvatureRecorder cells(n, S, 4);
  ASSERT_TRUE(pyramid.run(cells));
  EXPECT_EQ(cells.total(cells.CurvatureCalls), static_cast<long>(n));
  EXPECT_EQ(cells.total(cells.OutOfStep), 0);
  std::vector<double> errors;
  for (std::size_t j = 0; j < n * S; ++j)
  {
    const gls::PrincipalCurvatures &m = cells.Curvatures[j], &e = recorder.Curvatures[j];
    if (std::isfinite(e.k1))
    {
      errors.push_back(std::max(std::abs(m.k1 - e.k1), std::abs(m.k2 - e.k2)) * scales[j % S]);
    }
  }
  EXPECT_GT(errors.size(), n);
  EXPECT_LT(percentile99(errors), 0.01);

  settings.evaluation = gls::Evaluation::Exact;
  settings.principalCurvatures = false;
  const gls::ScaleSpaceEngine plain(c.points.data(), c.normals.data(), n, settings);
  CurvatureRecorder none(n, S, 4);
  ASSERT_TRUE(plain.run(none));
  EXPECT_EQ(none.total(none.CurvatureCalls), 0);
  EXPECT_EQ(none.total(none.SampleCalls), static_cast<long>(n));
  // Asking for the curvatures leaves the sphere's samples as they were (bit for bit in the portable build:
  // TheSpheresSamplesAreTheSphereSetsBitForBit; to rounding where the AVX2 build fuses multiply-adds otherwise).
  double worst = 0.0;
  for (std::size_t j = 0; j < n * S; ++j)
  {
    const gls::ScaleSample &a = none.Samples[j], &b = recorder.Samples[j];
    ASSERT_EQ(a.valid, b.valid);
    ASSERT_EQ(a.neighbors, b.neighbors);
    if (a.valid)
    {
      const double t = scales[j % S];
      worst = std::max({ worst, std::abs(a.kappa - b.kappa) * t, std::abs(a.tau - b.tau) / t });
    }
  }
  EXPECT_LT(worst, 1e-12);
}

TEST(ShapeOperator, TheSpheresSamplesAreTheSphereSetsBitForBit)
{
  // The sphere's values keep their moments and their vector grouping with the omega-values beside them.
  const Cloud c = paraboloid(60, 1.0, 0.8, 0.3, 0.005, 0.02, 5);
  const std::vector<double> scales{ 0.08, 0.2, 0.45 };
  gls::NeighborGrid grid;
  grid.build(c.points.data(), c.normals.data(), c.size(), 0.1);
  const TestBinning binning(scales);
  std::vector<gls::MomentsT<gls::ShapeOperatorMoments>> bins(3);
  std::vector<gls::Moments> sphereBins(3);
  std::vector<gls::CurvatureSample> with(3);
  std::vector<gls::ScaleSample> alone(3);
  long different[2] = {};
  for (std::size_t i = 0; i < c.size(); i += 29)
  {
    const gls::Vec3 p{ c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2] };
    for (int build = 0; build < 2; ++build)
    {
      const auto b = build == 0 ? gls::CpuKernelBuild::Portable : gls::CpuKernelBuild::Fastest;
      gls::onepass::evaluateAllScalesOnCpuFor<gls::ShapeOperatorMoments>(
        grid.view(), p, binning.View, 6.0, bins.data(), with.data(), b);
      gls::evaluateAllScalesOnCpu(grid.view(), p, binning.View, 6.0, sphereBins.data(), alone.data(), b);
      for (std::size_t k = 0; k < 3; ++k)
      {
        different[build] += std::memcmp(&with[k].sphere.kappa, &alone[k].kappa, sizeof(double)) == 0 &&
            std::memcmp(&with[k].sphere.deta, &alone[k].deta, sizeof(gls::Vec3)) == 0 ? 0 : 1;
      }
    }
  }
  EXPECT_EQ(different[0], 0);
  std::printf("sphere samples differing with the curvatures: portable %ld, fastest %ld\n", different[0], different[1]);
}

TEST(ShapeOperator, MultiresolutionCurvaturesFollowTheExactOnesOnANoisyScan)
{
  // The bunny sampled at 60k points with its mesh's normals, moved along them by 0.1% of the diagonal; scales from 1
  // to 4% of it. The multi-resolution walk (the CUDA kernel's loop) and the CPU kernel (both builds) with the
  // curvature set's own cells (summedCellsOf) against the exact one pass: t |k - k_exact| and the directions' angle
  // where the exact curvatures differ by a fifth of the larger (the bounds: p99 0.01 and 2 degrees).
  Cloud c = sampleObjSurface(dataFile("stanford-bunny.obj"), 60000, 7);
  const double diagonal = boxDiagonal(c.points);
  std::mt19937_64 rng(8);
  std::normal_distribution<double> noise(0.0, 0.001 * diagonal);
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    const double e = noise(rng);
    for (int a = 0; a < 3; ++a)
    {
      c.points[3 * i + a] += e * c.normals[3 * i + a];
    }
  }
  const std::vector<double> scales = gls::sampleScales(0.01 * diagonal, 0.04 * diagonal, 6,
    gls::ScaleSampling::Quadratic);
  const std::size_t S = scales.size();
  gls::ScaleSpaceSettings settings;
  settings.scales = scales;
  settings.evaluation = gls::Evaluation::Multiresolution;
  const gls::ScaleSpaceEngine engine(c.points.data(), c.normals.data(), c.size(), settings);
  const gls::MultiresolutionView& v = engine.pyramid().view();
  const std::vector<gls::CurvatureCell> cells = gls::summedCellsOf<gls::ShapeOperatorMoments>(v);
  const TestGrid grid(c, 0.25 * scales.back());
  const TestBinning binning(scales);
  std::vector<gls::MomentsT<gls::ShapeOperatorMoments>> exactBins(S);
  std::vector<gls::AggregateMomentsT<gls::ShapeOperatorMoments>> bins(S);
  gls::MultiresolutionScratchT<gls::ShapeOperatorMoments> scratch[2];
  std::vector<gls::CurvatureSample> exact(S), walk(S), cpu(S);
  std::vector<double> curvatureErrors, directionErrors;
  double cpuAgainstWalk = 0.0;
  for (std::size_t i = 0; i < c.size(); i += 97)
  {
    const gls::Vec3 p{ c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2] };
    gls::evaluateAllScales<gls::ShapeOperatorMoments>(
      grid.view(), p, binning.View, 6.0, exactBins.data(), exact.data());
    gls::evaluateAllScalesMultiresolution<gls::ShapeOperatorMoments>(
      v, cells.data(), p, binning.View, 6.0, bins.data(), walk.data());
    for (int build = 0; build < 2; ++build)
    {
      gls::multiresolution::evaluateAllScalesMultiresolutionOnCpuFor<gls::ShapeOperatorMoments>(v, cells.data(), p,
        binning.View, 6.0, scratch[build], cpu.data(),
        build == 0 ? gls::CpuKernelBuild::Portable : gls::CpuKernelBuild::Fastest);
      for (std::size_t k = 0; k < S; ++k)
      {
        if (walk[k].sphere.valid && cpu[k].sphere.valid)
        {
          cpuAgainstWalk = std::max({ cpuAgainstWalk,
            std::abs(cpu[k].principal.k1 - walk[k].principal.k1) * scales[k],
            std::abs(cpu[k].principal.k2 - walk[k].principal.k2) * scales[k] });
        }
      }
    }
    for (std::size_t k = 0; k < S; ++k)
    {
      const gls::PrincipalCurvatures &e = exact[k].principal, &m = walk[k].principal;
      if (!exact[k].sphere.valid || !std::isfinite(e.k1))
      {
        continue;
      }
      ASSERT_TRUE(std::isfinite(m.k1)) << "point " << i << " scale " << k;
      curvatureErrors.push_back(std::max(std::abs(m.k1 - e.k1), std::abs(m.k2 - e.k2)) * scales[k]);
      if (e.k1 - e.k2 >= 0.2 * std::max(std::abs(e.k1), std::abs(e.k2)))
      {
        directionErrors.push_back(std::isfinite(m.d1.x) ? angleDegrees(m.d1, e.d1) : 90.0);
      }
    }
  }
  const double curvatureP99 = percentile99(curvatureErrors), directionP99 = percentile99(directionErrors);
  std::printf("multi-resolution curvatures against the exact ones: p99 t |k - k_exact| %.3g (%zu), directions %.3g "
              "degrees (%zu); CPU kernel against the walk %.3g\n", curvatureP99, curvatureErrors.size(),
    directionP99, directionErrors.size(), cpuAgainstWalk);
  EXPECT_GT(curvatureErrors.size(), 2000u);
  EXPECT_GT(directionErrors.size(), 1000u);
  EXPECT_LE(curvatureP99, 0.01);
  EXPECT_LE(directionP99, 2.0);
  EXPECT_LT(cpuAgainstWalk, 1e-9);
}
