// The CUDA backend: on machines without a usable device (CI), the fallback is proven (the CUDA request runs on the
// CPU, says why, and gives the CPU's numbers bit for bit). Tests labelled `cuda` compare the device with the CPU
// and skip themselves, saying why, where no device is usable.
#include "CollectingSink.h"
#include "TestClouds.h"

#include "gls/Backend.h"
#include "gls/NormalEstimation.h"
#include "gls/ScaleSampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace glstest;

namespace
{

gls::ScaleSpaceSettings settingsFor(const std::vector<double>& scales, gls::Evaluation evaluation)
{
  gls::ScaleSpaceSettings settings;
  settings.scales = scales;
  settings.evaluation = evaluation;
  return settings;
}

CollectingSink runOn(const gls::ScaleSpaceEngine& engine, gls::RunReport& report)
{
  CollectingSink sink(engine.pointCount(), engine.scales().size());
  engine.run(sink, nullptr, nullptr, &report);
  return sink;
}

/// An engine on the backend (the settings' evaluator is chosen when the engine is built).
CollectingSink runOn(const Cloud& c, gls::ScaleSpaceSettings settings, gls::Backend backend, gls::RunReport& report)
{
  settings.backend = backend;
  const gls::ScaleSpaceEngine engine(c.points.data(), c.normals.data(), c.size(), settings);
  return runOn(engine, report);
}

CollectingSink runWith(const Cloud& c, const std::vector<double>& scales, gls::Backend backend,
  gls::RunReport& report, std::size_t chunkLimit = 0, gls::Evaluation evaluation = gls::Evaluation::Exact)
{
  gls::ScaleSpaceSettings settings = settingsFor(scales, evaluation);
  settings.deviceChunkLimit = chunkLimit;
  return runOn(c, settings, backend, report);
}

/// The bunny's surface sampled by area (mesh normals) and scales from `low` to `high` of its box diagonal.
Cloud sampledBunny(std::size_t n, double low, double high, int count, std::vector<double>& scales)
{
  Cloud c = sampleObjSurface(dataFile("stanford-bunny.obj"), n, 3);
  const double diagonal = boxDiagonal(c.points);
  scales = gls::sampleScales(low * diagonal, high * diagonal, count, gls::ScaleSampling::Quadratic);
  return c;
}

bool bitwiseEqual(const CollectingSink& a, const CollectingSink& b)
{
  for (std::size_t i = 0; i < a.Samples.size(); ++i)
  {
    const gls::ScaleSample& p = a.Samples[i];
    const gls::ScaleSample& q = b.Samples[i];
    const double va[] = { p.tau, p.kappa, p.phi, p.dtau, p.dkappa, p.eta.x, p.eta.y, p.eta.z, p.deta.x, p.deta.y,
      p.deta.z, p.neighbors };
    const double vb[] = { q.tau, q.kappa, q.phi, q.dtau, q.dkappa, q.eta.x, q.eta.y, q.eta.z, q.deta.x, q.deta.y,
      q.deta.z, q.neighbors };
    if (std::memcmp(va, vb, sizeof(va)) != 0)
    {
      return false;
    }
  }
  return true;
}

/// Largest difference of the dimensionless descriptors, relative to max(1, |value|).
double maxRelativeDifference(const CollectingSink& a, const CollectingSink& b, const std::vector<double>& scales)
{
  double worst = 0.0;
  for (std::size_t i = 0; i < a.Samples.size(); ++i)
  {
    const gls::ScaleSample& p = a.Samples[i];
    const gls::ScaleSample& q = b.Samples[i];
    if (p.valid != q.valid)
    {
      return INFINITY;
    }
    if (!p.valid)
    {
      continue;
    }
    const double t = scales[i % scales.size()];
    const double pairs[][2] = { { p.tau / t, q.tau / t }, { p.kappa * t, q.kappa * t }, { p.phi, q.phi },
      { p.dtau, q.dtau }, { p.dkappa * t * t, q.dkappa * t * t }, { p.eta.x, q.eta.x }, { p.deta.y * t, q.deta.y * t } };
    for (const auto& v : pairs)
    {
      worst = std::max(worst, std::abs(v[0] - v[1]) / std::max(1.0, std::abs(v[1])));
    }
  }
  return worst;
}

Cloud bunnyWithNormals()
{
  Cloud c;
  c.points = readObjVertices(dataFile("stanford-bunny.obj"));
  gls::NormalEstimationSettings ns;
  gls::NormalEstimationResult nr;
  gls::estimateNormals(c.points.data(), c.size(), ns, nr);
  c.normals = nr.normals;
  return c;
}

#define GLS_REQUIRE_CUDA_DEVICE()                                                                                  \
  if (!gls::cudaAvailability().usable)                                                                             \
  {                                                                                                                \
    GTEST_SKIP() << "no usable CUDA device here: " << gls::cudaAvailability().reason;                              \
  }

} // namespace

TEST(Backends, BuildReportsWhetherCudaIsCompiledIn)
{
  EXPECT_EQ(gls::cudaCompiledIn(), GLS_TEST_EXPECT_CUDA != 0);
  EXPECT_STREQ(gls::backendName(gls::Backend::CUDA), "CUDA");
  if (!gls::cudaAvailability().usable)
  {
    EXPECT_FALSE(gls::cudaAvailability().reason.empty());
  }
}

TEST(Backends, CudaRequestWithoutDeviceFallsBackToIdenticalCpuResults)
{
  if (gls::cudaAvailability().usable)
  {
    GTEST_SKIP() << "a CUDA device is usable here (" << gls::cudaAvailability().device
                 << "): the fallback is not exercised";
  }
  const Cloud c = paraboloid(40, 1.0, 0.6, 0.2, 0.02, 0.05, 21);
  const std::vector<double> scales = gls::sampleScales(0.1, 0.6, 10, gls::ScaleSampling::Quadratic);
  gls::RunReport cpu, cuda, automatic;
  const CollectingSink a = runWith(c, scales, gls::Backend::CPU, cpu);
  const CollectingSink b = runWith(c, scales, gls::Backend::CUDA, cuda);
  const CollectingSink d = runWith(c, scales, gls::Backend::Auto, automatic);
  EXPECT_EQ(cpu.used, gls::Backend::CPU);
  EXPECT_TRUE(cpu.fallbackReason.empty());
  EXPECT_EQ(cuda.used, gls::Backend::CPU);
  EXPECT_EQ(automatic.used, gls::Backend::CPU);
  EXPECT_EQ(cuda.fallbackReason, gls::cudaAvailability().reason);
  EXPECT_TRUE(bitwiseEqual(a, b));
  EXPECT_TRUE(bitwiseEqual(a, d));
}

TEST(CudaDevice, MatchesTheCpuOnRandomAndRealClouds)
{
  GLS_REQUIRE_CUDA_DEVICE();
  const Cloud noisy = paraboloid(120, 1.0, 0.6, -0.3, 0.02, 0.1, 5);
  const std::vector<double> s1 = gls::sampleScales(0.03, 0.5, 20, gls::ScaleSampling::Quadratic);
  gls::RunReport r1, r2;
  const CollectingSink cpu = runWith(noisy, s1, gls::Backend::CPU, r1);
  const CollectingSink gpu = runWith(noisy, s1, gls::Backend::CUDA, r2);
  ASSERT_EQ(r2.used, gls::Backend::CUDA) << r2.fallbackReason;
  EXPECT_LE(maxRelativeDifference(cpu, gpu, s1), 1e-9);

  const Cloud bunny = bunnyWithNormals();
  const std::vector<double> s2 = gls::sampleScales(0.002, 0.02, 20, gls::ScaleSampling::Quadratic);
  const CollectingSink cpu2 = runWith(bunny, s2, gls::Backend::CPU, r1);
  const CollectingSink gpu2 = runWith(bunny, s2, gls::Backend::CUDA, r2);
  ASSERT_EQ(r2.used, gls::Backend::CUDA) << r2.fallbackReason;
  EXPECT_LE(maxRelativeDifference(cpu2, gpu2, s2), 1e-9);
}

TEST(CudaDevice, ChunkedRunsEqualOneChunkAndRunsAreDeterministic)
{
  GLS_REQUIRE_CUDA_DEVICE();
  const Cloud bunny = bunnyWithNormals();
  const std::vector<double> scales = gls::sampleScales(0.002, 0.02, 12, gls::ScaleSampling::Logarithmic);
  gls::RunReport r;
  const CollectingSink whole = runWith(bunny, scales, gls::Backend::CUDA, r);
  ASSERT_EQ(r.used, gls::Backend::CUDA) << r.fallbackReason;
  const CollectingSink again = runWith(bunny, scales, gls::Backend::CUDA, r);
  EXPECT_TRUE(bitwiseEqual(whole, again));
  const CollectingSink chunked = runWith(bunny, scales, gls::Backend::CUDA, r, 1000); // 36 chunks
  ASSERT_EQ(r.used, gls::Backend::CUDA) << r.fallbackReason;
  EXPECT_TRUE(bitwiseEqual(whole, chunked));
}

TEST(CudaDevice, MultiresolutionMatchesTheCpu)
{
  // The multi-resolution evaluation at the default scales (0.8% to 8% of the diagonal) on the bunny's surface
  // sampled to 300,000 points: the device runs evaluateAllScalesMultiresolutionByWindows (bitwise the host/device
  // loop), the CPU engine its own kernel (the same samples summed in another order, 1e-10 apart in
  // TestMultiresolution), so the two agree to rounding; a
  // second device run and a run in chunks of 7,000 points give the same bits.
  GLS_REQUIRE_CUDA_DEVICE();
  std::vector<double> scales;
  const Cloud c = sampledBunny(300000, 0.008, 0.08, 20, scales);
  ASSERT_EQ(c.size(), 300000u);
  gls::ScaleSpaceSettings settings = settingsFor(scales, gls::Evaluation::Multiresolution);
  settings.backend = gls::Backend::CUDA;
  const gls::ScaleSpaceEngine engine(c.points.data(), c.normals.data(), c.size(), settings);
  ASSERT_EQ(engine.evaluation(), gls::Evaluation::Multiresolution);
  gls::RunReport r1, r2;
  const CollectingSink cpu = runOn(c, settings, gls::Backend::CPU, r1);
  const CollectingSink gpu = runOn(engine, r2);
  ASSERT_EQ(r2.used, gls::Backend::CUDA) << r2.fallbackReason;
  EXPECT_LE(maxRelativeDifference(cpu, gpu, scales), 1e-9);
  long valid = 0;
  for (const gls::ScaleSample& q : gpu.Samples)
  {
    valid += q.valid ? 1 : 0;
  }
  EXPECT_GT(valid, static_cast<long>(gpu.Samples.size() * 9 / 10));
  const CollectingSink again = runOn(engine, r2);
  EXPECT_TRUE(bitwiseEqual(gpu, again));
  settings.deviceChunkLimit = 7000;
  const CollectingSink chunked = runOn(c, settings, gls::Backend::CUDA, r2);
  ASSERT_EQ(r2.used, gls::Backend::CUDA) << r2.fallbackReason;
  EXPECT_TRUE(bitwiseEqual(gpu, chunked));
}

TEST(CudaDevice, ExactMatchesTheCpuOnASampledSurfaceAtTheDefaultScales)
{
  // The exact pass at the default relative scales on 100,000 points of the bunny's surface (a few thousand
  // neighbours in the largest balls: the device's longest loops).
  GLS_REQUIRE_CUDA_DEVICE();
  std::vector<double> scales;
  const Cloud c = sampledBunny(100000, 0.008, 0.08, 20, scales);
  gls::RunReport r1, r2;
  const CollectingSink cpu = runWith(c, scales, gls::Backend::CPU, r1);
  const CollectingSink gpu = runWith(c, scales, gls::Backend::CUDA, r2);
  ASSERT_EQ(r2.used, gls::Backend::CUDA) << r2.fallbackReason;
  EXPECT_LE(maxRelativeDifference(cpu, gpu, scales), 1e-9);
}
