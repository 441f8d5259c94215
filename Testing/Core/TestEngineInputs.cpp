// The engine reads its points and normals only while it is built: it calls inputsCopied once its sorted copies exist,
// and from then on overwriting the inputs changes none of its samples (its own order, a few given ids, many given
// ids), exact and multi-resolution. A point left out of the neighbourhoods (no normal) is still evaluated, at its
// own position.
#include "CollectingSink.h"
#include "TestClouds.h"
#include "gls/ScaleSpaceEngine.h"

#include <gtest/gtest.h>

#include <limits>

using namespace glstest;

namespace
{

std::vector<gls::ScaleSample> samplesOf(const gls::ScaleSpaceEngine& engine, std::size_t n,
  const std::vector<std::uint64_t>* ids)
{
  CollectingSink sink(n, engine.scales().size());
  EXPECT_TRUE(engine.run(sink, ids));
  return sink.Samples;
}

} // namespace

TEST(EngineInputs, AreReadOnlyUntilTheSortedCopiesExist)
{
  Cloud c = sampleObjSurface(dataFile("stanford-bunny.obj"), 20000, 3);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  c.points[3 * 10 + 1] = nan; // no position: invalid samples
  for (std::size_t i = 40; i < 45; ++i)
  {
    c.normals[3 * i] = nan; // no normal: out of every neighbourhood, evaluated all the same
  }
  const double d = boxDiagonal(c.points);
  std::vector<std::uint64_t> few{ 41, 10, 7, 19999, 43, 7 }, many;
  using Ids = const std::vector<std::uint64_t>*;
  for (std::uint64_t i = 0; i < c.size(); i += 2)
  {
    many.push_back(c.size() - 1 - i);
  }
  for (gls::Evaluation e : { gls::Evaluation::Exact, gls::Evaluation::Multiresolution })
  {
    gls::ScaleSpaceSettings s;
    s.scales = { 0.01 * d, 0.03 * d, 0.06 * d };
    s.evaluation = e;
    s.parallel.threads = 2;
    const gls::ScaleSpaceEngine kept(c.points.data(), c.normals.data(), c.size(), s);
    std::vector<double> points = c.points, normals = c.normals;
    int calls = 0;
    const gls::ScaleSpaceEngine overwritten(points.data(), normals.data(), c.size(), s, [&] {
      ++calls;
      std::fill(points.begin(), points.end(), 1e30);
      std::fill(normals.begin(), normals.end(), nan);
    });
    EXPECT_EQ(calls, 1);
    EXPECT_EQ(overwritten.pointCount(), c.size());
    for (Ids ids : { Ids(nullptr), Ids(&few), Ids(&many) })
    {
      const std::vector<gls::ScaleSample> a = samplesOf(kept, c.size(), ids);
      const std::vector<gls::ScaleSample> b = samplesOf(overwritten, c.size(), ids);
      for (std::size_t k = 0; k < a.size(); ++k)
      {
        ASSERT_TRUE(sameBits(a[k], b[k])) << "sample " << k << (ids ? " (given ids)" : "");
      }
    }
    // The points without a normal: their samples are those of their position, and they are defined.
    const std::vector<gls::ScaleSample> given = samplesOf(overwritten, c.size(), &few);
    const std::vector<gls::ScaleSample> own = samplesOf(overwritten, c.size(), nullptr);
    std::vector<gls::ScaleSample> at;
    for (std::size_t i = 40; i < 45; ++i)
    {
      overwritten.evaluatePosition({ c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2] }, at);
      for (std::size_t k = 0; k < s.scales.size(); ++k)
      {
        EXPECT_TRUE(sameBits(own[i * s.scales.size() + k], at[k])) << "point " << i;
        EXPECT_TRUE(own[i * s.scales.size() + k].valid) << "point " << i;
      }
    }
    EXPECT_TRUE(sameBits(given[41 * s.scales.size() + 1], own[41 * s.scales.size() + 1]));
    EXPECT_FALSE(given[10 * s.scales.size()].valid);
  }
}
