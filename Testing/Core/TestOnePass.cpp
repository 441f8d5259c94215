// The one-pass moment evaluation against the straightforward per-scale evaluation (one ball query and one fit per
// scale), and bitwise determinism across thread counts.
#include "CollectingSink.h"
#include "TestClouds.h"

#include "gls/NormalEstimation.h"
#include "gls/ScaleSampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

using namespace glstest;

namespace
{

/// Largest relative difference between the two evaluations over the dimensionless descriptors.
double maxRelativeDifference(const Cloud& c, const std::vector<double>& scales, int& compared)
{
  const CollectingSink a = runScaleSpace(c.points, c.normals, scales);
  const CollectingSink b =
    runScaleSpace(c.points, c.normals, scales, 0, 6.0, gls::EvaluationMethod::PerScale);
  double worst = 0.0;
  compared = 0;
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    for (std::size_t k = 0; k < scales.size(); ++k)
    {
      const gls::ScaleSample& p = a.at(i, k);
      const gls::ScaleSample& q = b.at(i, k);
      EXPECT_EQ(p.valid, q.valid);
      EXPECT_EQ(p.neighbors, q.neighbors);
      if (!p.valid || !q.valid)
      {
        continue;
      }
      ++compared;
      const double t = scales[k];
      const double pairs[][2] = { { p.tau / t, q.tau / t }, { p.kappa * t, q.kappa * t }, { p.phi, q.phi },
        { p.dtau, q.dtau }, { p.dkappa * t * t, q.dkappa * t * t }, { p.eta.x, q.eta.x }, { p.eta.y, q.eta.y },
        { p.eta.z, q.eta.z }, { p.deta.x * t, q.deta.x * t }, { p.deta.y * t, q.deta.y * t },
        { p.deta.z * t, q.deta.z * t } };
      for (const auto& v : pairs)
      {
        worst = std::max(worst, std::abs(v[0] - v[1]) / std::max(1.0, std::abs(v[1])));
      }
    }
  }
  return worst;
}

} // namespace

TEST(OnePass, AgreesWithPerScaleEvaluationOnANoisyParaboloid)
{
  const Cloud c = paraboloid(50, 1.0, 0.7, 0.3, 0.02, 0.1, 5);
  int compared = 0;
  const double worst =
    maxRelativeDifference(c, gls::sampleScales(0.08, 0.9, 20, gls::ScaleSampling::Quadratic), compared);
  EXPECT_GT(compared, 40000);
  EXPECT_LT(worst, 1e-10);
}

TEST(OnePass, AgreesWithPerScaleEvaluationOnTheBunnyScan)
{
  Cloud c;
  c.points = readObjVertices(dataFile("stanford-bunny.obj"));
  gls::NormalEstimationSettings ns;
  gls::NormalEstimationResult nr;
  ASSERT_TRUE(gls::estimateNormals(c.points.data(), c.size(), ns, nr));
  c.normals = nr.normals;
  // 0.8% to 8% of the bounding-box diagonal (about 0.2587 for this model).
  int compared = 0;
  const double worst =
    maxRelativeDifference(c, gls::sampleScales(0.002, 0.02, 8, gls::ScaleSampling::Quadratic), compared);
  EXPECT_GT(compared, 250000);
  EXPECT_LT(worst, 1e-10);
}

TEST(OnePass, ResultsAreBitwiseIdenticalForAnyThreadCount)
{
  const Cloud c = paraboloid(60, 1.0, 0.7, 0.3, 0.02, 0.1, 9);
  const std::vector<double> scales = gls::sampleScales(0.08, 0.5, 10, gls::ScaleSampling::Logarithmic);
  const CollectingSink one = runScaleSpace(c.points, c.normals, scales, 1);
  for (int threads : { 2, 3, 8 })
  {
    const CollectingSink many = runScaleSpace(c.points, c.normals, scales, threads);
    ASSERT_EQ(one.Samples.size(), many.Samples.size());
    for (std::size_t i = 0; i < one.Samples.size(); ++i)
    {
      const gls::ScaleSample& a = one.Samples[i];
      const gls::ScaleSample& b = many.Samples[i];
      const double va[] = { a.tau, a.kappa, a.phi, a.dtau, a.dkappa, a.eta.x, a.eta.y, a.eta.z, a.deta.x,
        a.deta.y, a.deta.z, a.neighbors };
      const double vb[] = { b.tau, b.kappa, b.phi, b.dtau, b.dkappa, b.eta.x, b.eta.y, b.eta.z, b.deta.x,
        b.deta.y, b.deta.z, b.neighbors };
      ASSERT_EQ(0, std::memcmp(va, vb, sizeof(va))) << "sample " << i << " with " << threads << " threads";
    }
  }
}

TEST(OnePass, BinningTableAgreesWithBinarySearch)
{
  // Quadratic, logarithmic and irregular scale lists; random squared distances inside the largest ball.
  const std::vector<std::vector<double>> lists = { gls::sampleScales(0.01, 1.0, 20, gls::ScaleSampling::Quadratic),
    gls::sampleScales(1e-4, 1.0, 300, gls::ScaleSampling::Logarithmic), { 0.5, 0.50000001, 0.9, 3.0 }, { 2.0 } };
  std::mt19937_64 rng(3);
  for (const auto& scales : lists)
  {
    gls::ScaleSpaceSettings settings;
    settings.scales = scales;
    const std::vector<double> xyz = { 0, 0, 0 }, nrm = { 0, 0, 1 };
    std::vector<double> squared;
    for (double t : scales)
    {
      squared.push_back(t * t);
    }
    std::vector<int> table(std::max<std::size_t>(1024, 64 * scales.size()));
    const double width = squared.back() / table.size();
    for (std::size_t j = 0; j < table.size(); ++j)
    {
      table[j] = gls::firstScaleHoldingBySearch(squared.data(), static_cast<int>(squared.size()), j * width);
    }
    gls::ScaleBinning b;
    b.scales = scales.data();
    b.squaredScales = squared.data();
    b.count = static_cast<int>(scales.size());
    b.table = table.data();
    b.tableSize = static_cast<int>(table.size());
    b.inverseCellWidth = table.size() / squared.back();
    std::uniform_real_distribution<double> u(0.0, squared.back());
    for (int i = 0; i < 100000; ++i)
    {
      const double d2 = i < static_cast<int>(squared.size()) ? squared[i] * (1 - 1e-16) : u(rng);
      const int k = gls::firstScaleHolding(b, d2);
      ASSERT_EQ(k, gls::firstScaleHoldingBySearch(squared.data(), b.count, d2)) << d2;
      ASSERT_LT(d2, squared[k]);
      ASSERT_TRUE(k == 0 || d2 >= squared[k - 1]);
    }
  }
}
