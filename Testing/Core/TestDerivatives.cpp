// The analytic scale derivatives against central finite differences of the fit in t, evaluated in long double by a
// brute-force weighted sum (an independent path: no grid, no moments), on noisy paraboloids and on a real scan.
#include "CollectingSink.h"
#include "TestClouds.h"

#include "gls/NormalEstimation.h"
#include "gls/ScaleSampling.h"
#include "gls/SphereFit.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace glstest;
using LD = long double;

namespace
{

gls::ScaleSampleT<LD> bruteForceFit(const Cloud& c, std::size_t p, LD t)
{
  gls::WeightedSumsT<LD> s, ds;
  LD n = 0;
  const LD px = c.points[3 * p], py = c.points[3 * p + 1], pz = c.points[3 * p + 2];
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    const gls::Vec3T<LD> x{ c.points[3 * i] - px, c.points[3 * i + 1] - py, c.points[3 * i + 2] - pz };
    const gls::Vec3T<LD> nn{ c.normals[3 * i], c.normals[3 * i + 1], c.normals[3 * i + 2] };
    const LD d2 = gls::squaredNorm(x);
    if (d2 < t * t)
    {
      gls::accumulate(s, gls::weightAt(d2, t), x, nn);
      gls::accumulate(ds, gls::weightDerivativeAt(d2, t), x, nn);
      n += 1;
    }
  }
  return gls::fitOrientedSphere<LD>(s, ds, n, 6);
}

/// Checks dtau, dkappa, deta of the double engine against central differences (step h = 1e-6 t) of the long-double
/// brute-force fit, in dimensionless form. Returns the number of (point, scale) pairs compared.
int compareWithFiniteDifferences(const Cloud& c, const std::vector<double>& scales, std::size_t stride, double tol)
{
  const CollectingSink s = runScaleSpace(c.points, c.normals, scales);
  int compared = 0;
  for (std::size_t i = 0; i < c.size(); i += stride)
  {
    for (std::size_t k = 0; k < scales.size(); ++k)
    {
      const gls::ScaleSample& a = s.at(i, k);
      const LD t = scales[k];
      const LD h = 1e-6L * t;
      const auto plus = bruteForceFit(c, i, t + h);
      const auto minus = bruteForceFit(c, i, t - h);
      if (!a.valid || !plus.valid || !minus.valid || a.phi < 0.2)
      {
        continue;
      }
      ++compared;
      const double fdTau = static_cast<double>((plus.tau - minus.tau) / (2 * h));
      const double fdKappa = static_cast<double>((plus.kappa - minus.kappa) / (2 * h));
      const double fdEta[3] = { static_cast<double>((plus.eta.x - minus.eta.x) / (2 * h)),
        static_cast<double>((plus.eta.y - minus.eta.y) / (2 * h)),
        static_cast<double>((plus.eta.z - minus.eta.z) / (2 * h)) };
      const double td = static_cast<double>(t);
      // Dimensionless forms: dtau, t deta, t^2 dkappa.
      EXPECT_NEAR(a.dtau, fdTau, tol * (1 + std::abs(fdTau))) << "point " << i << " scale " << td;
      EXPECT_NEAR(td * td * a.dkappa, td * td * fdKappa, tol * (1 + std::abs(td * td * fdKappa)))
        << "point " << i << " scale " << td;
      EXPECT_NEAR(td * a.deta.x, td * fdEta[0], tol * (1 + std::abs(td * fdEta[0])));
      EXPECT_NEAR(td * a.deta.y, td * fdEta[1], tol * (1 + std::abs(td * fdEta[1])));
      EXPECT_NEAR(td * a.deta.z, td * fdEta[2], tol * (1 + std::abs(td * fdEta[2])));
    }
  }
  return compared;
}

} // namespace

TEST(Derivatives, MatchFiniteDifferencesOnNoisyParaboloids)
{
  const std::vector<double> scales = gls::sampleScales(0.12, 0.8, 7, gls::ScaleSampling::Quadratic);
  for (unsigned seed : { 1u, 2u, 3u })
  {
    const Cloud c = paraboloid(40, 1.0, 0.9, -0.4, 0.02, 0.08, seed);
    EXPECT_GT(compareWithFiniteDifferences(c, scales, 41, 1e-5), 150);
  }
}

TEST(Derivatives, MatchFiniteDifferencesOnTheBunnyScan)
{
  Cloud c;
  c.points = readObjVertices(dataFile("stanford-bunny.obj"));
  ASSERT_EQ(c.size(), 35947u);
  gls::NormalEstimationSettings ns;
  ns.k = 16;
  gls::NormalEstimationResult nr;
  ASSERT_TRUE(gls::estimateNormals(c.points.data(), c.size(), ns, nr));
  c.normals = nr.normals;
  const std::vector<double> scales = gls::sampleScales(0.003, 0.02, 5, gls::ScaleSampling::Quadratic);
  EXPECT_GT(compareWithFiniteDifferences(c, scales, 997, 1e-5), 120);
}
