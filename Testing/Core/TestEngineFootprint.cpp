// ScaleSpaceEngine::footprint, the memory a budget counts before an engine is built, against the memory of the engine
// then built (its arrays' capacity): never below it, and close to it, for the exact and the multi-resolution engine
// on a scan, a sparse random cloud and a plane (its build's peak, and what it keeps while it runs); and with inputs the
// caller frees once the sorted copies exist.
#include "TestClouds.h"
#include "gls/ScaleSpaceEngine.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

using namespace glstest;

namespace
{

void expectFootprintCovers(const Cloud& c, const std::vector<double>& scales, const char* what)
{
  for (gls::Evaluation e : { gls::Evaluation::Exact, gls::Evaluation::Multiresolution })
  {
    gls::ScaleSpaceSettings s;
    s.scales = scales;
    s.evaluation = e;
    s.parallel.threads = 2;
    const gls::EngineFootprint footprint =
      gls::ScaleSpaceEngine::footprint(c.points.data(), c.normals.data(), c.size(), s);
    const double estimate = footprint.bytes(0.0);
    const gls::ScaleSpaceEngine engine(c.points.data(), c.normals.data(), c.size(), s);
    const double built = engine.memoryBytes();
    std::printf("%s, %s: footprint %.1f bytes a point, built %.1f\n", what,
      e == gls::Evaluation::Exact ? "exact" : "multi-resolution", estimate / c.size(), built / c.size());
    EXPECT_GE(estimate, built) << what;
    // What the engine keeps while it runs (beside a filter's outputs): at least its arrays, at most its build's peak.
    EXPECT_GE(footprint.running, built) << what;
    EXPECT_LE(footprint.running, estimate) << what;
    if (e == gls::Evaluation::Multiresolution)
    {
      EXPECT_LE(footprint.running, built + 1e3) << what; // counted from the pyramid's keys: its very arrays
    }
    // The build's scratch (sort keys, normalized normals) on top of what stays, and no more.
    EXPECT_LE(estimate, built + c.size() * 90.0 + 1e6) << what;
    // A caller that frees its points and normals (48 bytes a point) once the engine has its sorted copies holds them
    // while the copies are made only: at most their bytes more, and for a pyramid less (its cells come after).
    const double inputs = 48.0 * c.size();
    const double releasing = footprint.bytes(inputs);
    EXPECT_GE(releasing, estimate) << what;
    EXPECT_LE(releasing, estimate + inputs) << what;
    if (e == gls::Evaluation::Multiresolution)
    {
      EXPECT_LT(releasing, estimate + inputs) << what;
    }
  }
}

} // namespace

TEST(EngineFootprint, CoversTheBuiltEngineOnAScanARandomCloudAndAPlane)
{
  const Cloud bunny = sampleObjSurface(dataFile("stanford-bunny.obj"), 60000, 5);
  const double d = boxDiagonal(bunny.points);
  expectFootprintCovers(bunny, { 0.008 * d, 0.03 * d, 0.08 * d }, "bunny");
  // Scattered points, most alone in their finest cell at several levels: the pyramid's largest per point.
  Cloud scattered;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 20000; ++i)
  {
    scattered.points.insert(scattered.points.end(), { u(rng), u(rng), u(rng) });
    scattered.normals.insert(scattered.normals.end(), { 0.0, 0.0, 1.0 });
  }
  expectFootprintCovers(scattered, { 0.001, 0.01, 0.2 }, "scattered");
  Cloud plane;
  for (int i = 0; i < 200; ++i)
  {
    for (int j = 0; j < 200; ++j)
    {
      plane.points.insert(plane.points.end(), { i * 0.01, j * 0.01, 0.0 });
      plane.normals.insert(plane.normals.end(), { 0.0, 0.0, 1.0 });
    }
  }
  expectFootprintCovers(plane, { 0.02, 0.1, 0.5 }, "plane");
}
