// The one-pass moment evaluation against the straightforward per-scale evaluation (one ball query and one fit per
// scale), and bitwise determinism across thread counts.
#include "CollectingSink.h"
#include "TestBinning.h"
#include "TestGrid.h"
#include "TestClouds.h"

#include "gls/NeighborGrid.h"
#include "gls/NormalEstimation.h"
#include "gls/OnePassKernel.h"
#include "gls/ScaleSampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

using namespace glstest;

namespace
{

/// Largest relative difference between two samples of scale t over the dimensionless descriptors.
double descriptorDifference(const gls::ScaleSample& p, const gls::ScaleSample& q, double t)
{
  const double pairs[][2] = { { p.tau / t, q.tau / t }, { p.kappa * t, q.kappa * t }, { p.phi, q.phi },
    { p.dtau, q.dtau }, { p.dkappa * t * t, q.dkappa * t * t }, { p.eta.x, q.eta.x }, { p.eta.y, q.eta.y },
    { p.eta.z, q.eta.z }, { p.deta.x * t, q.deta.x * t }, { p.deta.y * t, q.deta.y * t },
    { p.deta.z * t, q.deta.z * t } };
  double worst = 0.0;
  for (const auto& v : pairs)
  {
    worst = std::max(worst, std::abs(v[0] - v[1]) / std::max(1.0, std::abs(v[1])));
  }
  return worst;
}

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
      worst = std::max(worst, descriptorDifference(p, q, scales[k]));
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

TEST(OnePass, CpuKernelAgreesWithTheDeviceLoop)
{
  // The CPU kernel (batched, branch-free ball test and binning, vector sums) against evaluateAllScales, whose windowed
  // form (bitwise the same, tested below) the CUDA kernel runs, here compiled for the host: the portable build performs the same operations in the same order
  // (bitwise equal where the compiler cannot fuse multiply-adds), the AVX2 build fuses them (close).
  const Cloud c = paraboloid(70, 1.0, 0.7, 0.3, 0.02, 0.1, 11);
  const std::vector<double> scales = gls::sampleScales(0.05, 0.6, 20, gls::ScaleSampling::Quadratic);
  const TestBinning binning(scales);
  const gls::ScaleBinning& b = binning.View;
  const TestGrid grid(c, 0.25 * scales.back());
  const std::size_t S = scales.size();
  std::vector<gls::Moments> bins(S);
  std::vector<gls::ScaleSample> device(S), portable(S), fastest(S);
  double worstPortable = 0.0, worstFastest = 0.0;
  int compared = 0;
  for (std::size_t i = 0; i < c.size(); i += 7)
  {
    // Data points and points off the cloud.
    const gls::Vec3 p = { c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2] + (i % 2 ? 0.0 : 0.05) };
    gls::evaluateAllScales(grid.view(), p, b, 6.0, bins.data(), device.data());
    gls::evaluateAllScalesOnCpu(grid.view(), p, b, 6.0, bins.data(), portable.data(), gls::CpuKernelBuild::Portable);
    gls::evaluateAllScalesOnCpu(grid.view(), p, b, 6.0, bins.data(), fastest.data(), gls::CpuKernelBuild::Fastest);
    for (std::size_t k = 0; k < S; ++k)
    {
      ASSERT_EQ(device[k].neighbors, portable[k].neighbors);
      ASSERT_EQ(device[k].neighbors, fastest[k].neighbors);
      ASSERT_EQ(device[k].valid, fastest[k].valid);
      if (device[k].valid)
      {
        ++compared;
        worstPortable = std::max(worstPortable, descriptorDifference(portable[k], device[k], scales[k]));
        worstFastest = std::max(worstFastest, descriptorDifference(fastest[k], device[k], scales[k]));
      }
    }
  }
  EXPECT_GT(compared, 10000);
#if (defined(__x86_64__) || defined(__i386__)) && !defined(__FMA__)
  EXPECT_EQ(worstPortable, 0.0);
#else
  EXPECT_LT(worstPortable, 1e-10);
#endif
  EXPECT_LT(worstFastest, 1e-10);
  std::printf("CPU kernel (%s) vs device loop: portable %.3g, fastest %.3g over %d samples\n",
    gls::onePassKernelBuild(), worstPortable, worstFastest, compared);
}

namespace
{

/// evaluateAllScalesByWindows<G> against evaluateAllScales on every 5th point of c (half of them lifted off the
/// cloud): the valid samples compared, or -1 when one differs in its bits.
template <int G>
long windowsAgainstTheOnePass(const Cloud& c, const gls::GridView& g, const gls::ScaleBinning& b)
{
  std::vector<gls::Moments> bins(static_cast<std::size_t>(b.count));
  auto at = [&c](std::size_t i) {
    return gls::Vec3{ c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2] + (i % 2 ? 0.0 : 0.05) };
  };
  return validSamplesIfSameBits(
    c.size(), 5, bins.size(),
    [&](std::size_t i, gls::ScaleSample* out) { gls::evaluateAllScales(g, at(i), b, 6.0, bins.data(), out); },
    [&](std::size_t i, gls::ScaleSample* out) { gls::evaluateAllScalesByWindows<G>(g, at(i), b, 6.0, out); });
}

} // namespace

TEST(OnePass, WindowsOfScalesGiveTheOnePassBitForBit)
{
  // The CUDA kernel's loop (the scales G at a time, no scratch bins) against the one pass with its S bins: every
  // bin receives the same neighbours in the same order, so the samples hold the same bits, whatever G (3 leaves a
  // last window of two scales).
  const Cloud c = paraboloid(70, 1.0, 0.7, 0.3, 0.02, 0.1, 12);
  const std::vector<double> scales = gls::sampleScales(0.05, 0.6, 20, gls::ScaleSampling::Quadratic);
  const TestBinning binning(scales);
  const TestGrid grid(c, 0.25 * scales.back());
  EXPECT_GT(windowsAgainstTheOnePass<1>(c, grid.view(), binning.View), 10000);
  EXPECT_GT(windowsAgainstTheOnePass<2>(c, grid.view(), binning.View), 10000);
  EXPECT_GT(windowsAgainstTheOnePass<3>(c, grid.view(), binning.View), 10000);
  EXPECT_GT(windowsAgainstTheOnePass<4>(c, grid.view(), binning.View), 10000);
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
      ASSERT_TRUE(sameBits(a, b)) << "sample " << i << " with " << threads << " threads";
    }
  }
}

TEST(OnePass, BinningTableAgreesWithBinarySearch)
{
  // Quadratic, logarithmic and irregular scale lists; random squared distances inside the largest ball.
  const std::vector<std::vector<double>> lists = { gls::sampleScales(0.01, 1.0, 20, gls::ScaleSampling::Quadratic),
    gls::sampleScales(1e-4, 1.0, 300, gls::ScaleSampling::Logarithmic), { 0.5, 0.50000001, 0.9, 3.0 }, { 2.0 } };
  std::mt19937_64 rng(3);
  int cellsWithSeveralScales = 0; // the lists with tiny gaps must exercise the binary-search fallback
  for (const auto& scales : lists)
  {
    const TestBinning binning(scales);
    const gls::ScaleBinning& b = binning.View;
    const std::vector<double>& squared = binning.Squared;
    const gls::BinningTable& table = binning.Table;
    // Cells narrower than the smallest gap hold at most one squared scale, unless the table is at its size limit.
    int ambiguous = 0;
    for (const gls::BinningCell& cell : table.cells)
    {
      ambiguous += cell.base < 0 ? 1 : 0;
    }
    if (table.cells.size() < static_cast<std::size_t>(gls::kMaxBinningCells))
    {
      EXPECT_EQ(ambiguous, 0);
    }
    cellsWithSeveralScales += ambiguous;
    // Random squared distances, the squared scales and their neighbouring doubles, and the cell edges.
    std::vector<double> probes;
    std::uniform_real_distribution<double> u(0.0, squared.back());
    for (int i = 0; i < 100000; ++i)
    {
      probes.push_back(u(rng));
    }
    for (double q : squared)
    {
      probes.insert(probes.end(), { q, std::nextafter(q, 0.0), std::nextafter(q, 1e300) });
    }
    for (std::size_t j = 0; j < table.cells.size(); ++j)
    {
      const double edge = j / table.inverseCellWidth;
      probes.insert(probes.end(), { edge, std::nextafter(edge, 0.0), std::nextafter(edge, 1e300) });
    }
    for (double d2 : probes)
    {
      if (!(d2 < squared.back()))
      {
        continue;
      }
      const int k = gls::firstScaleHolding(b, d2);
      ASSERT_EQ(k, gls::firstScaleHoldingBySearch(squared.data(), b.count, d2)) << d2;
      ASSERT_LT(d2, squared[k]);
      ASSERT_TRUE(k == 0 || d2 >= squared[k - 1]);
    }
  }
  EXPECT_GT(cellsWithSeveralScales, 0);
}
