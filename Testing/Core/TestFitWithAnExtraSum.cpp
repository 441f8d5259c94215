// A test-only fit that needs one sum the oriented sphere does not (HeightSpreadMoments.h): the recipe of
// docs/architecture.md ("How to add a fit"), done. It runs through the exact evaluation's kernels unchanged (the
// host/device loop, its windowed form, the CUDA kernel's loop, and the CPU kernel in both builds) and through the
// multi-resolution ones with its own cell sums. Checked against the heights summed point by point, and the sphere's
// samples against the oriented sphere's own run, bit for bit.
#include "HeightSpreadMoments.h"
#include "TestBinning.h"
#include "TestGrid.h"
#include "TestClouds.h"

#include "OnePassKernelBody.h"                        // the CPU kernels for any moment set (private to the core)
#include "multiresolution/MultiresolutionKernelBody.h"

#include "gls/MomentSet.h"
#include "gls/MultiresolutionCellSums.h"
#include "gls/MultiresolutionReferenceWalk.h"
#include "gls/NeighborGrid.h"
#include "gls/NormalEstimation.h"
#include "gls/OnePassKernel.h"
#include "gls/ScaleSampling.h"
#include "gls/ScaleSpaceEngine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

using namespace glstest;

namespace
{

/// Where each level of the pyramid begins among its nodes (levels finest first, each contiguous), and where the top
/// ends.
std::vector<std::uint64_t> levelStarts(const gls::MultiresolutionView& v)
{
  std::vector<std::uint64_t> levelStart(static_cast<std::size_t>(v.topLevel) + 2);
  levelStart[v.topLevel] = v.topBegin;
  levelStart[v.topLevel + 1] = v.topEnd;
  for (int l = v.topLevel; l > 0; --l)
  {
    levelStart[l - 1] = v.nodes[levelStart[l]].first;
  }
  return levelStart;
}

/// Every value of the two samples has the same bits (NaN included).
bool sameBits(const gls::ScaleSample& a, const gls::ScaleSample& b)
{
  const double u[] = { a.tau, a.kappa, a.phi, a.dtau, a.dkappa, a.eta.x, a.eta.y, a.eta.z, a.deta.x, a.deta.y,
    a.deta.z, a.neighbors };
  const double v[] = { b.tau, b.kappa, b.phi, b.dtau, b.dkappa, b.eta.x, b.eta.y, b.eta.z, b.deta.x, b.deta.y,
    b.deta.z, b.neighbors };
  return std::memcmp(u, v, sizeof(u)) == 0 && a.valid == b.valid;
}

} // namespace

TEST(FitWithAnExtraSum, RunsThroughTheExactKernelsAndAddsOnlyItsOwnSum)
{
  const Cloud c = paraboloid(60, 1.0, 0.7, 0.3, 0.02, 0.1, 5);
  const std::vector<double> scales = gls::sampleScales(0.05, 0.6, 12, gls::ScaleSampling::Quadratic);
  const TestBinning binning(scales);
  const gls::ScaleBinning& b = binning.View;
  const TestGrid grid(c, 0.25 * scales.back());
  const std::size_t S = scales.size();
  std::vector<gls::MomentsT<HeightSpreadMoments>> bins(S);
  std::vector<gls::Moments> sphereBins(S);
  std::vector<HeightSpreadMoments::Sample> loop(S), windows(S), portable(S), fastest(S);
  std::vector<gls::ScaleSample> sphereLoop(S), spherePortable(S), sphereFastest(S);
  int checked = 0;
  double worstFastest = 0.0;
  for (std::size_t i = 0; i < c.size(); i += 11)
  {
    const gls::Vec3 p = { c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2] };
    gls::evaluateAllScales(grid.view(), p, b, 6.0, bins.data(), loop.data());
    gls::evaluateAllScalesByWindows<4, HeightSpreadMoments>(grid.view(), p, b, 6.0, windows.data());
    gls::onepass::evaluateAllScalesOnCpuFor<HeightSpreadMoments>(
      grid.view(), p, b, 6.0, bins.data(), portable.data(), gls::CpuKernelBuild::Portable);
    gls::onepass::evaluateAllScalesOnCpuFor<HeightSpreadMoments>(
      grid.view(), p, b, 6.0, bins.data(), fastest.data(), gls::CpuKernelBuild::Fastest);
    gls::evaluateAllScales(grid.view(), p, b, 6.0, sphereBins.data(), sphereLoop.data());
    gls::evaluateAllScalesOnCpu(grid.view(), p, b, 6.0, sphereBins.data(), spherePortable.data(),
      gls::CpuKernelBuild::Portable);
    gls::evaluateAllScalesOnCpu(grid.view(), p, b, 6.0, sphereBins.data(), sphereFastest.data(),
      gls::CpuKernelBuild::Fastest);
    for (std::size_t k = 0; k < S; ++k)
    {
      // The extra sum changes none of the sphere's: each kernel's sphere samples are its own run's, bit for bit where
      // no multiply-add is fused (the AVX2 build fuses them where its compiler finds them, which depends on the code
      // around: there the samples agree to rounding).
      ASSERT_TRUE(sameBits(loop[k].sphere, sphereLoop[k])) << "point " << i << " scale " << k;
      ASSERT_TRUE(sameBits(windows[k].sphere, sphereLoop[k])) << "point " << i << " scale " << k;
      ASSERT_TRUE(sameBits(portable[k].sphere, spherePortable[k])) << "point " << i << " scale " << k;
      ASSERT_EQ(fastest[k].sphere.neighbors, sphereFastest[k].neighbors);
      if (sphereFastest[k].valid)
      {
        worstFastest = std::max(worstFastest, std::abs(fastest[k].sphere.kappa - sphereFastest[k].kappa) * scales[k]);
        worstFastest = std::max(worstFastest, std::abs(fastest[k].sphere.tau - sphereFastest[k].tau) / scales[k]);
        worstFastest = std::max(worstFastest, std::abs(fastest[k].sphere.phi - sphereFastest[k].phi));
      }
      EXPECT_EQ(std::isnan(loop[k].heightSpread), !sphereLoop[k].valid);
      if (!sphereLoop[k].valid)
      {
        continue;
      }
      const double want = heightSpreadByHand(c, p, scales[k]);
      const double tolerance = 1e-9 * scales[k];
      EXPECT_NEAR(loop[k].heightSpread, want, tolerance) << "point " << i << " scale " << k;
      EXPECT_EQ(windows[k].heightSpread, loop[k].heightSpread);
      EXPECT_NEAR(portable[k].heightSpread, want, tolerance);
      EXPECT_NEAR(fastest[k].heightSpread, want, tolerance);
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
  EXPECT_LT(worstFastest, 1e-12);
  std::printf("AVX2 build, sphere with and without the extra sum: largest difference %.3g\n", worstFastest);
}

TEST(FitWithAnExtraSum, RunsThroughTheMultiresolutionWalkWithItsOwnCellSums)
{
  // The multi-resolution reference walk (the host/device loop, and its windowed form, the CUDA kernel's loop) and the
  // CPU kernel (both builds) with the test set's cells: the sphere's samples are the oriented sphere's own run's, bit
  // for bit (to rounding in the AVX2 build), the spread is the exact evaluation's to the accuracy of the cells taken
  // whole, and the CPU kernel's is the walk's to rounding.
  const Cloud c = paraboloid(150, 1.0, 0.7, 0.3, 0.01, 0.05, 9);
  const std::vector<double> scales = gls::sampleScales(0.05, 0.5, 10, gls::ScaleSampling::Quadratic);
  gls::ScaleSpaceSettings settings;
  settings.scales = scales;
  settings.evaluation = gls::Evaluation::Multiresolution;
  settings.multiresolution.accuracy = 0.3;
  gls::ScaleSpaceEngine engine(c.points.data(), c.normals.data(), c.size(), settings);
  const gls::MultiresolutionView& v = engine.pyramid().view();
  const std::vector<HeightSpreadMoments::Cell> cells = gls::summedCellsOf<HeightSpreadMoments>(v);
  // Merged from their children (addChildToCell), the cells keep the sum y y_z^2 of their points.
  long merged = 0;
  const std::vector<std::uint64_t> levelStart = levelStarts(v);
  for (std::uint64_t node = v.summedBegin; node < engine.pyramid().nodeCount(); ++node)
  {
    const HeightSpreadMoments::Cell& cell = cells[node - v.summedBegin];
    HeightSpreadMoments::Cell direct;
    int level = v.summedLevel;
    while (node >= levelStart[level + 1])
    {
      ++level;
    }
    std::uint32_t first = 0, last = 0;
    gls::pointRange(v.nodes, static_cast<std::uint32_t>(node), level, first, last);
    gls::momentsOfPoints<HeightSpreadMoments>(v.points, first, last, cell.centroid, direct);
    const double h = v.levelSize[level], tolerance = 1e-10 * cell.count * h * h * h;
    ASSERT_NEAR(cell.offsetHeightSquared.x, direct.offsetHeightSquared.x, tolerance);
    ASSERT_NEAR(cell.offsetHeightSquared.y, direct.offsetHeightSquared.y, tolerance);
    ASSERT_NEAR(cell.offsetHeightSquared.z, direct.offsetHeightSquared.z, tolerance);
    merged += level > v.summedLevel ? 1 : 0;
  }
  EXPECT_GT(merged, 50);
  const TestBinning binning(scales);
  const gls::ScaleBinning& b = binning.View;
  const TestGrid grid(c, 0.25 * scales.back());
  const std::size_t S = scales.size();
  std::vector<gls::AggregateMomentsT<HeightSpreadMoments>> bins(S);
  std::vector<gls::AggregateMoments> sphereBins(S);
  std::vector<gls::MomentsT<HeightSpreadMoments>> exactBins(S);
  std::vector<HeightSpreadMoments::Sample> walk(S), windows(S), exact(S);
  std::vector<gls::ScaleSample> sphereWalk(S);
  const gls::CpuKernelBuild builds[2] = { gls::CpuKernelBuild::Portable, gls::CpuKernelBuild::Fastest };
  gls::MultiresolutionScratchT<HeightSpreadMoments> scratch[2];
  gls::MultiresolutionScratch sphereScratch[2];
  std::vector<HeightSpreadMoments::Sample> cpu[2] = { std::vector<HeightSpreadMoments::Sample>(S),
    std::vector<HeightSpreadMoments::Sample>(S) };
  std::vector<gls::ScaleSample> sphereCpu[2] = { std::vector<gls::ScaleSample>(S), std::vector<gls::ScaleSample>(S) };
  double worst = 0.0, worstCpu = 0.0, worstFastestSphere = 0.0;
  long taken = 0;
  int checked = 0;
  for (std::size_t i = 0; i < c.size(); i += 37)
  {
    const gls::Vec3 p = { c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2] };
    gls::evaluateAllScalesMultiresolution<HeightSpreadMoments>(v, cells.data(), p, b, 6.0, bins.data(), walk.data());
    gls::evaluateAllScalesMultiresolutionByWindows<4, HeightSpreadMoments>(v, cells.data(), p, b, 6.0, windows.data());
    gls::evaluateAllScalesMultiresolution(v, p, b, 6.0, sphereBins.data(), sphereWalk.data());
    gls::evaluateAllScales(grid.view(), p, b, 6.0, exactBins.data(), exact.data());
    for (int k = 0; k < 2; ++k)
    {
      gls::multiresolution::evaluateAllScalesMultiresolutionOnCpuFor<HeightSpreadMoments>(
        v, cells.data(), p, b, 6.0, scratch[k], cpu[k].data(), builds[k]);
      gls::evaluateAllScalesMultiresolutionOnCpu(v, p, b, 6.0, sphereScratch[k], sphereCpu[k].data(), builds[k]);
    }
    gls::forEachMultiresolutionSample(v, p, scales.back(), scales.front(),
      [&](std::uint32_t, int, int) { ++taken; }, [](std::uint32_t) {});
    for (std::size_t k = 0; k < S; ++k)
    {
      ASSERT_TRUE(sameBits(walk[k].sphere, sphereWalk[k])) << "point " << i << " scale " << k;
      ASSERT_TRUE(sameBits(windows[k].sphere, sphereWalk[k])) << "point " << i << " scale " << k;
      ASSERT_TRUE(sameBits(cpu[0][k].sphere, sphereCpu[0][k])) << "point " << i << " scale " << k;
      ASSERT_EQ(cpu[1][k].sphere.valid, sphereCpu[1][k].valid);
      if (sphereCpu[1][k].valid)
      {
        worstFastestSphere =
          std::max(worstFastestSphere, std::abs(cpu[1][k].sphere.kappa - sphereCpu[1][k].kappa) * scales[k]);
      }
      if (!walk[k].sphere.valid || !exact[k].sphere.valid || !cpu[0][k].sphere.valid || !cpu[1][k].sphere.valid)
      {
        continue;
      }
      EXPECT_EQ(windows[k].heightSpread, walk[k].heightSpread);
      worst = std::max(worst, std::abs(walk[k].heightSpread - exact[k].heightSpread) / scales[k]);
      for (int c = 0; c < 2; ++c)
      {
        worstCpu = std::max(worstCpu, std::abs(cpu[c][k].heightSpread - walk[k].heightSpread) / scales[k]);
      }
      ++checked;
    }
  }
  EXPECT_GT(taken, 1000); // the walks took cells whole: their z^2 sums came from the test set's cells
  EXPECT_GT(checked, 300);
  EXPECT_LT(worst, 1e-3);
  EXPECT_LT(worstCpu, 1e-10);
  EXPECT_LT(worstFastestSphere, 1e-10);
  std::printf("multi-resolution spread against the exact one: largest difference %.3g t (%ld cells taken whole); "
              "CPU kernel against the walk %.3g t; AVX2 build's kappa t with and without the extra sum %.3g\n",
    worst, taken, worstCpu, worstFastestSphere);
}

TEST(FitWithAnExtraSum, ASetsCellSumsOverABuiltPyramidAreTheBuildsOwnForTheSphere)
{
  // summedCellsOf forms a set's cells level by level as the build forms the pyramid's own: for the oriented sphere
  // they are the pyramid's cells bit for bit, on one thread or several.
  const Cloud c = paraboloid(120, 1.0, 0.7, 0.3, 0.01, 0.05, 5);
  gls::ScaleSpaceSettings settings;
  settings.scales = gls::sampleScales(0.05, 0.5, 6, gls::ScaleSampling::Quadratic);
  settings.evaluation = gls::Evaluation::Multiresolution;
  gls::ScaleSpaceEngine engine(c.points.data(), c.normals.data(), c.size(), settings);
  const gls::MultiresolutionView& v = engine.pyramid().view();
  ASSERT_GT(v.topEnd - v.summedBegin, 100u);
  ASSERT_GT(v.topLevel, v.summedLevel + 2);
  for (int threads : { 1, 3 })
  {
    gls::ParallelOptions parallel;
    parallel.threads = threads;
    parallel.chunk = 7;
    const std::vector<gls::PyramidCell> cells = gls::summedCellsOf<gls::OrientedSphereMoments>(v, parallel);
    ASSERT_EQ(cells.size(), v.topEnd - v.summedBegin);
    static_assert(sizeof(gls::PyramidCell) % sizeof(double) == 0, "a cell is doubles only (no padding compared)");
    EXPECT_EQ(std::memcmp(cells.data(), v.cells, cells.size() * sizeof(gls::PyramidCell)), 0) << threads;
  }
}
