// A fit cut into spatial tiles (TiledScaleSpace, SpatialTiles) against one engine over the whole cloud: the same
// bits for every point, whatever the tiles, threads, evaluation or subset of points.
#include "CollectingSink.h"
#include "TestClouds.h"

#include "gls/NeighborGrid.h"
#include "gls/ScaleSampling.h"
#include "gls/SpatialTiles.h"
#include "gls/TiledScaleSpace.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace glstest;

namespace
{

/// The bunny sampled by area, with the awkward points a scan brings: a point with a NaN coordinate, one with no
/// usable normal, and copies of one position.
Cloud awkwardBunny(std::size_t n)
{
  Cloud c = sampleObjSurface(dataFile("stanford-bunny.obj"), n, 11);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  c.add(nan, 0.1, 0.0, 0.0, 0.0, 1.0);
  c.add(c.points[30], c.points[31], c.points[32] + 1e-3, 0.0, 0.0, 0.0);
  for (int copy = 0; copy < 3; ++copy)
  {
    c.add(c.points[60], c.points[61], c.points[62], c.normals[60], c.normals[61], c.normals[62]);
  }
  return c;
}

gls::ScaleSpaceSettings settingsFor(const Cloud& c, gls::Evaluation evaluation, int threads)
{
  gls::ScaleSpaceSettings s;
  const double d = boxDiagonal(c.points);
  s.scales = gls::sampleScales(0.01 * d, 0.08 * d, 8, gls::ScaleSampling::Quadratic);
  s.evaluation = evaluation;
  s.multiresolution.accuracy = gls::kDefaultAccuracy;
  s.parallel.threads = threads;
  return s;
}

/// Every sample of the points below `evaluated`; the others marked as never fed (neighbors -1).
CollectingSink runTiles(const Cloud& c, std::size_t evaluated, const gls::ScaleSpaceSettings& s, std::size_t tiles,
  const std::vector<std::uint64_t>* ids = nullptr, std::size_t* tileCount = nullptr,
  std::size_t* largest = nullptr)
{
  const gls::TiledScaleSpace tiled(c.points.data(), c.normals.data(), c.size(), evaluated, s, tiles);
  CollectingSink sink(c.size(), s.scales.size());
  for (gls::ScaleSample& sample : sink.Samples)
  {
    sample.neighbors = -1.0;
  }
  gls::RunReport report;
  EXPECT_TRUE(tiled.run(sink, ids, s.parallel, report));
  if (tileCount)
  {
    *tileCount = tiled.tileCount();
  }
  if (largest)
  {
    *largest = tiled.largestTile();
  }
  return sink;
}

/// The number of points whose samples differ in some bit (or in validity) between a and b.
std::size_t differingPoints(const CollectingSink& a, const CollectingSink& b, std::size_t points)
{
  std::size_t differ = 0;
  for (std::size_t i = 0; i < points; ++i)
  {
    for (std::size_t k = 0; k < a.Scales; ++k)
    {
      if (!sameBits(a.at(i, k), b.at(i, k)) || a.at(i, k).valid != b.at(i, k).valid)
      {
        ++differ;
        break;
      }
    }
  }
  return differ;
}

} // namespace

TEST(SpatialTiles, EveryFinitePointLiesInOneTileAndTheTilesAreBalanced)
{
  const Cloud c = sampleObjSurface(dataFile("stanford-bunny.obj"), 40000, 5);
  for (std::size_t want : { 2, 5, 8, 16 })
  {
    SCOPED_TRACE(want);
    const gls::SpatialTiles tiles = gls::SpatialTiles::plan(c.points.data(), c.size(), want);
    ASSERT_EQ(tiles.count(), want);
    std::vector<std::size_t> counts(tiles.count(), 0);
    for (std::size_t i = 0; i < c.size(); ++i)
    {
      int in = 0;
      for (std::size_t k = 0; k < tiles.count(); ++k)
      {
        if (tiles.holds(k, &c.points[3 * i]))
        {
          ++in;
          ++counts[k];
          EXPECT_TRUE(tiles.near(k, &c.points[3 * i], 0.0));
        }
      }
      ASSERT_EQ(in, 1) << "point " << i;
      ASSERT_TRUE(tiles.holds(tiles.tileOf(&c.points[3 * i]), &c.points[3 * i]));
      // Down the cuts, the same boxes as one test per box, each once.
      for (double reach : { 0.0, 0.01, 0.05 })
      {
        std::vector<int> seen(tiles.count(), 0);
        tiles.forEachNear(&c.points[3 * i], reach, [&seen](std::size_t k) { ++seen[k]; });
        for (std::size_t k = 0; k < tiles.count(); ++k)
        {
          ASSERT_EQ(seen[k], tiles.near(k, &c.points[3 * i], reach) ? 1 : 0) << "point " << i << ", box " << k;
        }
      }
    }
    // Median cuts of the whole sample: a power of two gives equal tiles, others at most twice the smallest.
    const auto [low, high] = std::minmax_element(counts.begin(), counts.end());
    EXPECT_LE(static_cast<double>(*high), (want & (want - 1)) == 0 ? 1.02 * *low : 2.05 * *low);
  }
  // One position cannot be cut; a non-finite position counts as in the first tile only.
  const double same[9] = { 1, 2, 3, 1, 2, 3, 1, 2, 3 };
  EXPECT_EQ(gls::SpatialTiles::plan(same, 3, 8).count(), 1u);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double bad[3] = { nan, 0.0, 0.0 };
  const gls::SpatialTiles two = gls::SpatialTiles::plan(c.points.data(), c.size(), 2);
  EXPECT_TRUE(two.holds(0, bad));
  EXPECT_FALSE(two.holds(1, bad));
  EXPECT_FALSE(two.near(0, bad, 1.0));
}

TEST(NeighborGrid, AGridOnTheWholeCloudsLatticeSortsEveryPointIntoTheSameCell)
{
  // A tile's grid (buildOnLattice) and the whole cloud's: every point of the tile in the same lattice cell, so a ball
  // query visits the points in the same order; a grid over the tile's own box generally does not.
  const Cloud c = sampleObjSurface(dataFile("stanford-bunny.obj"), 20000, 9);
  const double cell = 0.013;
  gls::NeighborGrid whole;
  whole.build(c.points.data(), c.normals.data(), c.size(), cell);
  const gls::GridLattice lattice = gls::NeighborGrid::chooseLattice(c.points.data(), c.size(), cell, nullptr);
  std::vector<double> part;
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    if (c.points[3 * i] > 0.0 && c.points[3 * i + 2] < 0.02)
    {
      part.insert(part.end(), &c.points[3 * i], &c.points[3 * i] + 3);
    }
  }
  gls::NeighborGrid tile, own;
  tile.buildOnLattice(part.data(), nullptr, part.size() / 3, lattice);
  own.build(part.data(), nullptr, part.size() / 3, cell);
  const auto cornerOf = [](const gls::GridView& g, const double* p) {
    std::array<double, 3> corner;
    for (int a = 0; a < 3; ++a)
    {
      corner[a] = gls::gridCellLowerBound(g, a, gls::gridCellOf(g, p[a], a));
    }
    return corner;
  };
  std::size_t moved = 0;
  for (std::size_t i = 0; i < part.size() / 3; ++i)
  {
    ASSERT_EQ(cornerOf(tile.view(), &part[3 * i]), cornerOf(whole.view(), &part[3 * i])) << "point " << i;
    moved += cornerOf(own.view(), &part[3 * i]) != cornerOf(whole.view(), &part[3 * i]) ? 1 : 0;
  }
  EXPECT_GT(moved, 0u) << "the part's own grid happens to share the lattice: the test shows nothing";
  EXPECT_LT(tile.view().dims[0] * tile.view().dims[1] * tile.view().dims[2],
    whole.view().dims[0] * whole.view().dims[1] * whole.view().dims[2]);
}

TEST(TiledScaleSpace, TilesGiveTheSamplesOfOneEngineBitForBit)
{
  const Cloud c = awkwardBunny(30000);
  for (const gls::Evaluation evaluation : { gls::Evaluation::Exact, gls::Evaluation::Multiresolution })
  {
    for (int threads : { 1, 2 })
    {
      const gls::ScaleSpaceSettings s = settingsFor(c, evaluation, threads);
      const CollectingSink whole = runTiles(c, c.size(), s, 1);
      for (std::size_t tiles : { 2, 8, 13 })
      {
        SCOPED_TRACE(testing::Message() << "evaluation " << static_cast<int>(evaluation) << ", " << threads
                                        << " threads, " << tiles << " tiles");
        std::size_t made = 0, largest = 0;
        const CollectingSink tiled = runTiles(c, c.size(), s, tiles, nullptr, &made, &largest);
        EXPECT_EQ(made, tiles);
        EXPECT_LT(largest, c.size());
        EXPECT_EQ(differingPoints(tiled, whole, c.size()), 0u);
      }
    }
  }
}

TEST(TiledScaleSpace, ABandNarrowerThanTheReachWouldChangeTheSamples)
{
  // The oracle's power: the tiles of a cloud cut in two with no band (scales far below the tiles' reach do not
  // matter) differ from the whole run near the cut once the scales reach across it; with the band they do not.
  const Cloud c = awkwardBunny(20000);
  const gls::ScaleSpaceSettings s = settingsFor(c, gls::Evaluation::Exact, 2);
  const CollectingSink whole = runTiles(c, c.size(), s, 1);
  // Two engines over the halves of a median cut, each alone, as tiles without a band would be.
  const gls::SpatialTiles halves = gls::SpatialTiles::plan(c.points.data(), c.size(), 2);
  CollectingSink alone(c.size(), s.scales.size());
  for (std::size_t k = 0; k < 2; ++k)
  {
    Cloud half;
    std::vector<std::uint64_t> index;
    for (std::size_t i = 0; i < c.size(); ++i)
    {
      if (halves.holds(k, &c.points[3 * i]))
      {
        half.add(c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2], c.normals[3 * i], c.normals[3 * i + 1],
          c.normals[3 * i + 2]);
        index.push_back(i);
      }
    }
    const gls::ScaleSpaceEngine engine(half.points.data(), half.normals.data(), half.size(), s);
    CollectingSink part(half.size(), s.scales.size());
    ASSERT_TRUE(engine.run(part));
    for (std::size_t j = 0; j < index.size(); ++j)
    {
      for (std::size_t k2 = 0; k2 < s.scales.size(); ++k2)
      {
        alone.Samples[index[j] * s.scales.size() + k2] = part.at(j, k2);
      }
    }
  }
  EXPECT_GT(differingPoints(alone, whole, c.size()), c.size() / 20);
  EXPECT_EQ(differingPoints(runTiles(c, c.size(), s, 2), whole, c.size()), 0u);
}

TEST(TiledScaleSpace, APieceWithGhostsAndASubsetOfPointsGetTheWholeRunsSamples)
{
  // A distributed piece: the last points are neighbours only (never fed). A run given some points feeds those only.
  const Cloud c = awkwardBunny(20000);
  const std::size_t evaluated = c.size() - 4000;
  for (const gls::Evaluation evaluation : { gls::Evaluation::Exact, gls::Evaluation::Multiresolution })
  {
    SCOPED_TRACE(static_cast<int>(evaluation));
    const gls::ScaleSpaceSettings s = settingsFor(c, evaluation, 2);
    const CollectingSink whole = runTiles(c, evaluated, s, 1);
    const CollectingSink tiled = runTiles(c, evaluated, s, 6);
    EXPECT_EQ(differingPoints(tiled, whole, c.size()), 0u);
    for (std::size_t i = evaluated; i < c.size(); ++i)
    {
      ASSERT_EQ(tiled.at(i, 0).neighbors, -1.0) << "ghost " << i << " was evaluated";
    }
    std::vector<std::uint64_t> ids;
    for (std::size_t i = evaluated; i-- > 0;)
    {
      if (i % 97 == 0)
      {
        ids.push_back(i);
      }
    }
    const CollectingSink some = runTiles(c, evaluated, s, 6, &ids);
    for (std::size_t i = 0; i < c.size(); ++i)
    {
      if (i < evaluated && i % 97 == 0)
      {
        for (std::size_t k = 0; k < s.scales.size(); ++k)
        {
          ASSERT_TRUE(sameBits(some.at(i, k), whole.at(i, k))) << "point " << i;
        }
      }
      else
      {
        ASSERT_EQ(some.at(i, 0).neighbors, -1.0) << "point " << i << " was not asked for";
      }
    }
  }
}

TEST(TiledScaleSpace, ProgressRunsOnceAcrossTheTilesAndAnAbortStopsThem)
{
  const Cloud c = awkwardBunny(20000);
  gls::ScaleSpaceSettings s = settingsFor(c, gls::Evaluation::Multiresolution, 2);
  const gls::TiledScaleSpace tiled(c.points.data(), c.normals.data(), c.size(), c.size(), s, 4);
  CollectingSink sink(c.size(), s.scales.size());
  gls::RunReport report;
  std::vector<double> seen;
  gls::ParallelOptions parallel = s.parallel;
  parallel.progress = [&](double f) {
    seen.push_back(f);
    return false;
  };
  ASSERT_TRUE(tiled.run(sink, nullptr, parallel, report));
  ASSERT_FALSE(seen.empty());
  for (std::size_t i = 1; i < seen.size(); ++i)
  {
    ASSERT_GE(seen[i], seen[i - 1]) << "progress went back at report " << i;
  }
  EXPECT_GE(seen.front(), 0.0);
  EXPECT_NEAR(seen.back(), 1.0, 1e-12);
  // Aborted within the second tile: the run stops and says so.
  std::size_t calls = 0;
  parallel.progress = [&](double f) {
    ++calls;
    return f > 0.3;
  };
  EXPECT_FALSE(tiled.run(sink, nullptr, parallel, report));
  EXPECT_LT(calls, seen.size());
}

TEST(TiledScaleSpace, AFitAroundAFewPointsGivesThemTheWholeRunsSamples)
{
  // A scale profile's few points: one engine over their neighbourhoods instead of the cloud, the same bits; the
  // points not selected are never fed. Among the selected: the NaN point, the one without a normal, a copy.
  const std::size_t n = 30000;
  const Cloud c = awkwardBunny(n);
  const std::vector<std::uint64_t> selected = { 7, 4000, 29999, n, n + 1, n + 3, 12345, 4000 };
  for (const gls::Evaluation evaluation : { gls::Evaluation::Exact, gls::Evaluation::Multiresolution })
  {
    for (int threads : { 1, 2 })
    {
      SCOPED_TRACE(testing::Message() << "evaluation " << static_cast<int>(evaluation) << ", " << threads
                                      << " threads");
      const gls::ScaleSpaceSettings s = settingsFor(c, evaluation, threads);
      const CollectingSink whole = runTiles(c, c.size(), s, 1);
      const gls::TiledScaleSpace around(c.points.data(), c.normals.data(), c.size(), c.size(), s, selected);
      EXPECT_EQ(around.tileCount(), 1u);
      // The multi-resolution reach adds the walk's region and the cells taken whole to the largest scale.
      EXPECT_LT(around.largestTile(), evaluation == gls::Evaluation::Exact ? c.size() / 4 : c.size() * 3 / 4)
        << "not a fit around the points";
      EXPECT_GT(around.largestTile(), selected.size());
      for (const bool some : { false, true })
      {
        const std::vector<std::uint64_t> asked = { n + 3, 12345, 7 };
        CollectingSink sink(c.size(), s.scales.size());
        for (gls::ScaleSample& sample : sink.Samples)
        {
          sample.neighbors = -1.0;
        }
        gls::RunReport report;
        ASSERT_TRUE(around.run(sink, some ? &asked : nullptr, s.parallel, report));
        for (std::size_t i = 0; i < c.size(); ++i)
        {
          const bool fed = some ? std::find(asked.begin(), asked.end(), i) != asked.end()
                                : std::find(selected.begin(), selected.end(), i) != selected.end();
          for (std::size_t k = 0; k < s.scales.size(); ++k)
          {
            if (fed)
            {
              ASSERT_TRUE(sameBits(sink.at(i, k), whole.at(i, k))) << "point " << i << ", scale " << k;
              ASSERT_EQ(sink.at(i, k).valid, whole.at(i, k).valid) << "point " << i << ", scale " << k;
            }
            else
            {
              ASSERT_EQ(sink.at(i, k).neighbors, -1.0) << "point " << i << " was fed";
            }
          }
        }
        EXPECT_TRUE(whole.at(7, s.scales.size() - 1).valid); // the oracle holds defined samples too
      }
    }
  }
  // Nothing selected (a piece without any of a profile's points): nothing fed.
  const gls::ScaleSpaceSettings s = settingsFor(c, gls::Evaluation::Exact, 2);
  const gls::TiledScaleSpace none(
    c.points.data(), c.normals.data(), c.size(), c.size(), s, std::vector<std::uint64_t>());
  CollectingSink sink(c.size(), s.scales.size());
  gls::RunReport report;
  EXPECT_TRUE(none.run(sink, nullptr, s.parallel, report));
  EXPECT_EQ(none.largestTile(), 0u);
}
