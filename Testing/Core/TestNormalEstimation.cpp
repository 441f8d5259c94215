// PCA normals and their orientation: analytic sphere and plane, degenerate neighbourhoods, every orientation mode.
#include "TestClouds.h"

#include "gls/NormalEstimation.h"
#include "gls/OrientationChoice.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <random>
#include <cmath>
#include <vector>

using namespace glstest;

namespace
{

double dot3(const double* a, const double* b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

} // namespace

TEST(NormalEstimation, SphereNormalsAreRadialAndMinimumSpanningTreeOrientsThemOutward)
{
  const Cloud c = sphere(5000, 2.0, false, 1.0, -3.0, 0.5);
  for (auto type : { gls::NeighborhoodType::KNearest, gls::NeighborhoodType::Radius })
  {
    gls::NormalEstimationSettings s;
    s.neighborhood = type;
    s.k = 12;
    s.radius = 0.25;
    gls::NormalEstimationResult r;
    ASSERT_TRUE(gls::estimateNormals(c.points.data(), c.size(), s, r));
    EXPECT_EQ(r.components, 1u);
    for (std::size_t i = 0; i < c.size(); ++i)
    {
      ASSERT_GT(dot3(&r.normals[3 * i], &c.normals[3 * i]), 0.999) << i;
    }
  }
}

TEST(NormalEstimation, TwoSpheresAreTwoComponentsBothOutward)
{
  Cloud c = sphere(2000, 1.0);
  const Cloud d = sphere(2000, 0.5, false, 5.0, 0.0, 0.0);
  c.points.insert(c.points.end(), d.points.begin(), d.points.end());
  c.normals.insert(c.normals.end(), d.normals.begin(), d.normals.end());
  gls::NormalEstimationSettings s;
  gls::NormalEstimationResult r;
  ASSERT_TRUE(gls::estimateNormals(c.points.data(), c.size(), s, r));
  EXPECT_EQ(r.components, 2u);
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    ASSERT_GT(dot3(&r.normals[3 * i], &c.normals[3 * i]), 0.99) << i;
  }
}

TEST(NormalEstimation, ViewpointAndReferenceOrientations)
{
  const Cloud c = plane(30, 1.0);
  gls::NormalEstimationSettings s;
  s.orientation = gls::NormalOrientation::TowardsPoint;
  s.viewpoint = { 0.0, 0.0, -5.0 };
  gls::NormalEstimationResult r;
  ASSERT_TRUE(gls::estimateNormals(c.points.data(), c.size(), s, r));
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    ASSERT_NEAR(r.normals[3 * i + 2], -1.0, 1e-12);
  }
  s.orientation = gls::NormalOrientation::AwayFromPoint;
  ASSERT_TRUE(gls::estimateNormals(c.points.data(), c.size(), s, r));
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    ASSERT_NEAR(r.normals[3 * i + 2], 1.0, 1e-12);
  }
  std::vector<double> reference(c.normals);
  for (std::size_t i = 0; i < c.size(); i += 2)
  {
    reference[3 * i + 2] = -1.0; // every other point wants -z
  }
  s.orientation = gls::NormalOrientation::AgreeWithReference;
  s.reference = reference.data();
  ASSERT_TRUE(gls::estimateNormals(c.points.data(), c.size(), s, r));
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    ASSERT_NEAR(r.normals[3 * i + 2], i % 2 ? 1.0 : -1.0, 1e-12);
  }
}

TEST(NormalEstimation, WithoutReachAndDegreesTheRestIsBitForBitTheSame)
{
  // What a caller does not want is left empty, and the normals, counts, spreads and components do not change: a
  // sphere with a line sticking out (grown neighbourhoods, raised graph degrees), for each neighbourhood type and
  // with and without the tree. The need asked before the run is smaller.
  Cloud c = sphere(3000, 1.0);
  for (int i = 0; i < 60; ++i)
  {
    c.points.insert(c.points.end(), { 1.0 + 0.02 * i, 0.0, 0.0 });
  }
  for (auto type : { gls::NeighborhoodType::KNearest, gls::NeighborhoodType::Radius })
  {
    for (auto orientation : { gls::NormalOrientation::MinimumSpanningTree, gls::NormalOrientation::Up })
    {
      gls::NormalEstimationSettings all;
      all.neighborhood = type;
      all.radius = 0.15;
      all.orientation = orientation;
      gls::NormalEstimationSettings lean = all;
      lean.reachWanted = false;
      lean.graphDegreeWanted = false;
      gls::NormalEstimationResult full, less;
      ASSERT_TRUE(gls::estimateNormals(c.points.data(), c.points.size() / 3, all, full));
      ASSERT_TRUE(gls::estimateNormals(c.points.data(), c.points.size() / 3, lean, less));
      EXPECT_EQ(full.reach.size(), c.points.size() / 3);
      EXPECT_EQ(full.graphDegree.size(), c.points.size() / 3);
      EXPECT_GT(*std::max_element(full.graphDegree.begin(), full.graphDegree.end()), all.graphNeighbors);
      EXPECT_TRUE(less.reach.empty());
      EXPECT_TRUE(less.graphDegree.empty());
      ASSERT_EQ(full.normals.size(), less.normals.size());
      for (std::size_t j = 0; j < full.normals.size(); ++j)
      {
        const double a = full.normals[j], b = less.normals[j];
        ASSERT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << j;
      }
      EXPECT_EQ(full.neighborCounts, less.neighborCounts);
      for (std::size_t j = 0; j < full.spread.size(); ++j)
      {
        const double a = full.spread[j], b = less.spread[j];
        ASSERT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << j;
      }
      EXPECT_EQ(full.components, less.components);
      EXPECT_LT(gls::normalEstimationBytes(1000, lean), gls::normalEstimationBytes(1000, all));
    }
  }
}

TEST(NormalEstimation, DegenerateNeighbourhoodsGiveNaN)
{
  // Two points: fewer than 3 neighbours.
  std::vector<double> two = { 0, 0, 0, 1, 0, 0 };
  gls::NormalEstimationSettings s;
  gls::NormalEstimationResult r;
  ASSERT_TRUE(gls::estimateNormals(two.data(), 2, s, r));
  EXPECT_TRUE(std::isnan(r.normals[0]));
  EXPECT_EQ(r.neighborCounts[0], 2);
  // Collinear points: the normal is undefined.
  std::vector<double> line;
  for (int i = 0; i < 40; ++i)
  {
    line.insert(line.end(), { 0.1 * i, 0.2 * i, -0.05 * i });
  }
  ASSERT_TRUE(gls::estimateNormals(line.data(), 40, s, r));
  for (int i = 0; i < 40; ++i)
  {
    EXPECT_TRUE(std::isnan(r.normals[3 * i])) << i;
  }
  // Radius too small: only the point itself.
  const Cloud c = plane(10, 1.0);
  s.neighborhood = gls::NeighborhoodType::Radius;
  s.radius = 1e-3;
  ASSERT_TRUE(gls::estimateNormals(c.points.data(), c.size(), s, r));
  EXPECT_EQ(r.neighborCounts[5], 1);
  EXPECT_TRUE(std::isnan(r.normals[15]));
}

TEST(NormalEstimation, TheEstimatesTreeIsTheStandaloneTreeWhateverTheThreads)
{
  // Two spheres, a line sticking out of one of them (without growth most of its points get no normal, so the graph
  // lists of the sphere's points near it are queried again among the points with a normal; with growth, the grown
  // points' lists are), a lattice plane (equal costs everywhere), a NaN point and repeated points.
  Cloud c = sphere(3000, 1.0);
  const Cloud d = sphere(1500, 0.5, false, 3.0, 0.0, 0.0);
  const Cloud flat = plane(30, 2.0);
  c.points.insert(c.points.end(), d.points.begin(), d.points.end());
  for (std::size_t i = 0; i < flat.size(); ++i)
  {
    c.points.insert(c.points.end(), { flat.points[3 * i], flat.points[3 * i + 1] + 5.0, flat.points[3 * i + 2] });
  }
  for (int i = 1; i <= 60; ++i)
  {
    c.points.insert(c.points.end(), { 0.001, 1.0 + 0.02 * i, 0.002 });
  }
  c.points.insert(c.points.end(), { std::nan(""), 0.0, 0.0 });
  c.points.insert(c.points.end(), c.points.begin(), c.points.begin() + 30); // ten repeated points
  const std::size_t n = c.points.size() / 3;

  for (double growth : { 1.0, 8.0 })
  {
    gls::NormalEstimationSettings s;
    s.parallel.threads = 1;
    s.maximumGrowth = growth;
    gls::NormalEstimationResult oriented;
    ASSERT_TRUE(gls::estimateNormals(c.points.data(), n, s, oriented));
    // The same estimate unoriented, then oriented on its own (the distributed runs' path: its own grid, every graph
    // list queried).
    s.orientation = gls::NormalOrientation::None;
    gls::NormalEstimationResult unoriented;
    ASSERT_TRUE(gls::estimateNormals(c.points.data(), n, s, unoriented));
    std::size_t components = 0;
    std::vector<double> standalone = unoriented.normals;
    ASSERT_TRUE(gls::orientByMinimumSpanningTree(c.points.data(), n, s.graphNeighbors, standalone.data(), s.parallel,
      components, unoriented.graphDegree.data()));
    EXPECT_EQ(components, oriented.components);
    EXPECT_GE(components, 3u);
    std::size_t undefined = 0;
    for (std::size_t i = 0; i < 3 * n; ++i)
    {
      undefined += std::isnan(oriented.normals[i]) ? 1 : 0;
      if (!(std::isnan(oriented.normals[i]) && std::isnan(standalone[i])))
      {
        ASSERT_EQ(oriented.normals[i], standalone[i]) << i / 3;
      }
    }
    if (growth == 1.0)
    {
      EXPECT_GE(undefined, 3u * 40u); // most of the line's points
    }
    // Any thread count: the same bits.
    s.orientation = gls::NormalOrientation::MinimumSpanningTree;
    s.parallel.threads = 3;
    s.parallel.chunk = 17;
    gls::NormalEstimationResult threaded;
    ASSERT_TRUE(gls::estimateNormals(c.points.data(), n, s, threaded));
    for (std::size_t i = 0; i < 3 * n; ++i)
    {
      if (!(std::isnan(oriented.normals[i]) && std::isnan(threaded.normals[i])))
      {
        ASSERT_EQ(oriented.normals[i], threaded.normals[i]) << i / 3;
      }
    }
    // Outward on both spheres, one side on the plane.
    for (std::size_t i = 0; i < 4500; ++i)
    {
      const double* p = &c.points[3 * i];
      const double centre = i < 3000 ? 0.0 : 3.0;
      const double radial[3] = { p[0] - centre, p[1], p[2] };
      if (std::isfinite(oriented.normals[3 * i]))
      {
        ASSERT_GT(dot3(&oriented.normals[3 * i], radial), 0.0) << i;
      }
    }
    for (std::size_t i = 4500; i + 1 < 4500 + flat.size(); ++i)
    {
      ASSERT_GT(oriented.normals[3 * i + 2] * oriented.normals[3 * 4500 + 2], 0.99) << i;
    }
  }
}

TEST(NormalEstimation, AGrownPointOfASmallCloudLinksToEveryOtherPoint)
{
  // Forty points on a line and three off it, a graph of 30 neighbours: the line's neighbourhoods grow twice (their
  // graph degree doubles twice, to 120), beyond the 42 other points there are; such a point links to all of them.
  std::vector<double> xyz;
  for (int i = 0; i < 40; ++i)
  {
    xyz.insert(xyz.end(), { 0.1 * i, 0.0, 0.0 });
  }
  xyz.insert(xyz.end(), { 2.0, 3.0, 0.0, 1.0, -3.0, 0.5, 3.0, 2.5, -0.5 });
  gls::NormalEstimationSettings s;
  s.graphNeighbors = 30;
  gls::NormalEstimationResult r;
  ASSERT_TRUE(gls::estimateNormals(xyz.data(), 43, s, r));
  EXPECT_GT(*std::max_element(r.graphDegree.begin(), r.graphDegree.end()), 42);
  EXPECT_EQ(r.components, 1u);
  std::vector<double> standalone = r.normals;
  s.orientation = gls::NormalOrientation::None;
  gls::NormalEstimationResult unoriented;
  ASSERT_TRUE(gls::estimateNormals(xyz.data(), 43, s, unoriented));
  std::size_t components = 0;
  standalone = unoriented.normals;
  ASSERT_TRUE(gls::orientByMinimumSpanningTree(
    xyz.data(), 43, s.graphNeighbors, standalone.data(), s.parallel, components, unoriented.graphDegree.data()));
  EXPECT_EQ(components, 1u);
  for (std::size_t i = 0; i < 3 * 43; ++i)
  {
    if (!(std::isnan(r.normals[i]) && std::isnan(standalone[i])))
    {
      EXPECT_EQ(r.normals[i], standalone[i]) << i / 3;
    }
  }
}

TEST(NormalEstimation, AbortStopsTheRun)
{
  const Cloud c = sphere(20000, 1.0);
  gls::NormalEstimationSettings s;
  s.parallel.chunk = 64;
  int calls = 0;
  s.parallel.progress = [&calls](double) { return ++calls >= 3; };
  gls::NormalEstimationResult r;
  EXPECT_FALSE(gls::estimateNormals(c.points.data(), c.size(), s, r));
  EXPECT_GE(calls, 3);
}

TEST(NormalEstimation, KNearestReachIsTheLargestKthNeighbourDistance)
{
  // Points at x = 0, 1, 3, 7 (and a NaN point, ignored): the k-th nearest of each point, itself included.
  const double nan = std::nan("");
  const double xyz[] = { 0, 0, 0, 1, 0, 0, 3, 0, 0, 7, 0, 0, nan, 0, 0 };
  gls::ParallelOptions parallel;
  EXPECT_DOUBLE_EQ(gls::kNearestReach(xyz, 5, 1, parallel), 0.0); // itself
  EXPECT_DOUBLE_EQ(gls::kNearestReach(xyz, 5, 2, parallel), 4.0); // 7 -> 3
  EXPECT_DOUBLE_EQ(gls::kNearestReach(xyz, 5, 3, parallel), 6.0); // 7 -> 1
  EXPECT_DOUBLE_EQ(gls::kNearestReach(xyz, 5, 4, parallel), 7.0); // 0 -> 7 and 7 -> 0
  EXPECT_TRUE(std::isinf(gls::kNearestReach(xyz, 5, 5, parallel))); // fewer finite points than k
  EXPECT_DOUBLE_EQ(gls::kNearestReach(xyz + 12, 1, 3, parallel), 0.0); // no finite point
  // On a sphere sample: equal to the brute-force largest 16th-nearest distance.
  const Cloud s = sphere(2000, 1.0);
  double expected = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i)
  {
    std::vector<double> d2;
    for (std::size_t j = 0; j < s.size(); ++j)
    {
      double d = 0.0;
      for (int a = 0; a < 3; ++a)
      {
        d += (s.points[3 * i + a] - s.points[3 * j + a]) * (s.points[3 * i + a] - s.points[3 * j + a]);
      }
      d2.push_back(d);
    }
    std::nth_element(d2.begin(), d2.begin() + 15, d2.end());
    expected = std::max(expected, std::sqrt(d2[15]));
  }
  EXPECT_NEAR(gls::kNearestReach(s.points.data(), s.size(), 16, parallel), expected, 1e-12);
}

namespace
{

/// A simulated aerial strip, 100 m x 100 m seen from above at about 3 points per m^2 (2 cm of noise): rolling terrain,
/// houses with vertical walls (a few points) and gabled roofs of 35 degrees pitch, and trees (points scattered in a
/// crown, no true normal). normals: the true unit normals (NaN for the trees).
Cloud aerialStrip(unsigned seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.02);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double pitch = 35.0 * 3.14159265358979323846 / 180.0;
  const auto ground = [](double x, double y) { return 2.0 * std::sin(x / 15.0) * std::cos(y / 20.0); };
  Cloud c;
  for (int i = 0; i < 30000; ++i)
  {
    const double x = 100.0 * u(rng), y = 100.0 * u(rng);
    // Houses: footprints 10 m (x) by 8 m (y) on a 25 m grid; the roof's ridge along x, eaves 5 m above the ground.
    const double hx = std::fmod(x, 25.0), hy = std::fmod(y, 25.0);
    const double g = ground(x, y);
    if (hx > 5.0 && hx < 15.0 && hy > 5.0 && hy < 13.0)
    {
      const double across = hy - 9.0; // from the ridge
      const double z = g + 5.0 + (4.0 - std::abs(across)) * std::tan(pitch);
      const double ny = (across > 0.0 ? 1.0 : -1.0) * std::sin(pitch);
      c.add(x, y, z + noise(rng), 0.0, ny, std::cos(pitch));
      continue;
    }
    // Trees: crowns of radius 3 m around (20, 20) + 25 m steps, 6 to 12 m up.
    const double tx = std::fmod(x + 5.0, 25.0) - 0.0, ty = std::fmod(y + 5.0, 25.0) - 0.0;
    if ((tx - 0.0) * (tx - 0.0) + (ty - 0.0) * (ty - 0.0) < 9.0)
    {
      c.add(x, y, g + 6.0 + 6.0 * u(rng), nan, nan, nan);
      continue;
    }
    // Terrain: the normal of the height field.
    const double gx = 2.0 / 15.0 * std::cos(x / 15.0) * std::cos(y / 20.0);
    const double gy = -2.0 / 20.0 * std::sin(x / 15.0) * std::sin(y / 20.0);
    const double l = std::sqrt(1.0 + gx * gx + gy * gy);
    c.add(x, y, g + noise(rng), -gx / l, -gy / l, 1.0 / l);
  }
  // A few points on the walls (a scanner sees them at the swath's edge): vertical normals, left out of the count.
  for (int i = 0; i < 800; ++i)
  {
    const double x = 25.0 * std::floor(4.0 * u(rng)) + 5.0 + 10.0 * u(rng);
    const double y = 25.0 * std::floor(4.0 * u(rng)) + (u(rng) < 0.5 ? 5.0 : 13.0);
    c.add(x, y + noise(rng), ground(x, y) + 5.0 * u(rng), 0.0, y - std::floor(y / 25.0) * 25.0 < 9.0 ? -1.0 : 1.0,
      0.0);
  }
  return c;
}

} // namespace

TEST(NormalEstimation, AnAerialStripFacesUpByDefaultAndInTheUpMode)
{
  // The default (minimum spanning tree) starts each component outward from its centroid, which on a tile of terrain
  // may be down (an aerial tile was 94.5% down); a flat cloud of coherent normals is then turned to face +z. The Up
  // mode faces +z point by point. Counted over the points whose true normal is not vertical (z > 0.2).
  const Cloud c = aerialStrip(17);
  for (const gls::NormalOrientation orientation :
    { gls::NormalOrientation::MinimumSpanningTree, gls::NormalOrientation::Up })
  {
    SCOPED_TRACE(static_cast<int>(orientation));
    gls::NormalEstimationSettings s;
    s.orientation = orientation;
    gls::NormalEstimationResult r;
    ASSERT_TRUE(gls::estimateNormals(c.points.data(), c.size(), s, r));
    long counted = 0, up = 0;
    for (std::size_t i = 0; i < c.size(); ++i)
    {
      if (!(c.normals[3 * i + 2] > 0.2) || !std::isfinite(r.normals[3 * i + 2]))
      {
        continue;
      }
      ++counted;
      up += r.normals[3 * i + 2] > 0.0 ? 1 : 0;
    }
    std::printf("aerial strip, orientation %d: %ld of %ld non-vertical normals up (%.3f%%)\n",
      static_cast<int>(orientation), up, counted, 100.0 * up / counted);
    EXPECT_GT(counted, 25000);
    EXPECT_GE(static_cast<double>(up), 0.999 * counted);
  }
}

namespace
{

/// The normals of a cloud estimated with the default settings and `orientation`.
gls::NormalEstimationResult estimatedWith(const Cloud& c, gls::NormalOrientation orientation)
{
  gls::NormalEstimationSettings s;
  s.orientation = orientation;
  gls::NormalEstimationResult r;
  EXPECT_TRUE(gls::estimateNormals(c.points.data(), c.size(), s, r));
  return r;
}

} // namespace

TEST(NormalEstimation, AnAerialStripsWallsFaceOutAlongTheTree)
{
  // Airborne lidar's rule (UpAlongSpanningTree): the ground, roofs and terrain up point by point, as Up does; the
  // walls (true normals horizontal, outward) from their neighbours along the tree, where Up leaves each wall point's
  // side to the sign of its estimate's small z.
  const Cloud c = aerialStrip(17);
  double share[2] = { 0.0, 0.0 };
  int k = 0;
  for (const gls::NormalOrientation orientation :
    { gls::NormalOrientation::UpAlongSpanningTree, gls::NormalOrientation::Up })
  {
    const gls::NormalEstimationResult r = estimatedWith(c, orientation);
    long counted = 0, up = 0, walls = 0, out = 0;
    for (std::size_t i = 0; i < c.size(); ++i)
    {
      if (!std::isfinite(r.normals[3 * i]) || !std::isfinite(c.normals[3 * i]))
      {
        continue;
      }
      if (c.normals[3 * i + 2] > 0.2)
      {
        ++counted;
        up += r.normals[3 * i + 2] > 0.0 ? 1 : 0;
      }
      else if (std::abs(r.normals[3 * i + 2]) < gls::kUpAnchorCosine) // walls: the tree orients them
      {
        ++walls;
        out += dot3(&r.normals[3 * i], &c.normals[3 * i]) > 0.0 ? 1 : 0;
      }
    }
    share[k++] = static_cast<double>(out) / static_cast<double>(walls);
    std::printf("aerial strip, orientation %d: %.3f%% of %ld non-vertical normals up; %.1f%% of %ld wall points out\n",
      static_cast<int>(orientation), 100.0 * up / counted, counted, 100.0 * out / walls, walls);
    EXPECT_GE(static_cast<double>(up), 0.999 * counted);
    EXPECT_GT(walls, 300);
  }
  EXPECT_GE(share[0], 0.99); // along the tree (measured 100%; Up, by the sign of each point's tilt: 98.6% here)
}

namespace
{

/// A room 8 m x 6 m x 3 m (floor, ceiling, four walls) sampled every `spacing` (jittered, 2 mm of noise along the
/// normals), true normals facing into the room; or, `building`, the same box without a floor standing on a 40 m x 40
/// m ground (the ground's points outside its footprint), true normals facing out of it and the ground up.
Cloud roomOrBuilding(bool building, double spacing, unsigned seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.002);
  const double L[3] = { 8.0, 6.0, 3.0 };
  const double side = building ? 1.0 : -1.0; // outward of the box, or into it
  Cloud c;
  // A rectangle: origin o, edges a and b (axes ia, ib of lengths la, lb), normal n.
  const auto face = [&](const double o[3], int ia, double la, int ib, double lb, const double n[3]) {
    const int na = static_cast<int>(la / spacing), nb = static_cast<int>(lb / spacing);
    for (int i = 0; i < na; ++i)
    {
      for (int j = 0; j < nb; ++j)
      {
        double p[3] = { o[0], o[1], o[2] };
        p[ia] += la * (i + u(rng)) / na;
        p[ib] += lb * (j + u(rng)) / nb;
        const double e = noise(rng);
        if (building && n[2] > 0.5 && o[2] == 0.0 && p[0] > 0.0 && p[0] < L[0] && p[1] > 0.0 && p[1] < L[1])
        {
          continue; // the ground under the building is not seen
        }
        c.add(p[0] + e * n[0], p[1] + e * n[1], p[2] + e * n[2], n[0], n[1], n[2]);
      }
    }
  };
  const double floorOrigin[3] = { 0, 0, 0 }, ceilingOrigin[3] = { 0, 0, L[2] };
  const double floorNormal[3] = { 0, 0, -side }, ceilingNormal[3] = { 0, 0, side };
  if (building)
  {
    const double groundOrigin[3] = { -16, -17, 0 }, up[3] = { 0, 0, 1 };
    face(groundOrigin, 0, 40.0, 1, 40.0, up);
  }
  else
  {
    face(floorOrigin, 0, L[0], 1, L[1], floorNormal);
  }
  face(ceilingOrigin, 0, L[0], 1, L[1], ceilingNormal);
  for (int a = 0; a < 2; ++a)
  {
    for (int end = 0; end < 2; ++end)
    {
      double o[3] = { 0, 0, 0 }, n[3] = { 0, 0, 0 };
      o[a] = end * L[a];
      n[a] = (end ? 1.0 : -1.0) * side;
      face(o, 1 - a, L[1 - a], 2, L[2], n);
    }
  }
  return c;
}

/// The share of the finite estimated normals that agree with the true ones.
double agreeing(const Cloud& c, const gls::NormalEstimationResult& r)
{
  double defined = 0.0, agree = 0.0;
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    if (std::isfinite(r.normals[3 * i]))
    {
      defined += 1.0;
      agree += dot3(&r.normals[3 * i], &c.normals[3 * i]) > 0.0 ? 1.0 : 0.0;
    }
  }
  return agree / defined;
}

} // namespace

TEST(NormalEstimation, ATerrestrialScanFacesTheRoomItWasTakenIn)
{
  // Terrestrial lidar's rule (GroundUpAlongSpanningTree): each component turned so that its ground or floor faces
  // up. A room scanned from inside then faces into the room (its ceiling down), where the outward rule of the
  // minimum spanning tree turns it inside out; a building seen from the ground around it faces out (walls out, roof
  // up). Nothing is forced up point by point.
  for (const bool building : { false, true })
  {
    SCOPED_TRACE(building ? "building" : "room");
    const Cloud c = roomOrBuilding(building, building ? 0.2 : 0.08, 5);
    double share[2];
    int k = 0;
    for (const gls::NormalOrientation orientation :
      { gls::NormalOrientation::GroundUpAlongSpanningTree, gls::NormalOrientation::MinimumSpanningTree })
    {
      share[k++] = agreeing(c, estimatedWith(c, orientation));
      std::printf("%s (%zu points), orientation %d: %.3f%% of the normals as seen from the scanner's side\n",
        building ? "building on its ground" : "room", c.size(), static_cast<int>(orientation), 100.0 * share[k - 1]);
    }
    EXPECT_GE(share[0], 0.999);
    if (!building)
    {
      EXPECT_LT(share[1], 0.5); // the outward rule turns the room inside out: hence the ground rule
    }
  }
}

TEST(OrientationChoice, TheFilesScannersAndLidarAttributesDecide)
{
  const double sensor[3] = { 1, 2, 3 };
  gls::LidarEvidence none;
  EXPECT_EQ(gls::chooseOrientation(true, sensor, none).source, gls::OrientationSource::ScannerPositions);
  const gls::OrientationChoice atSensor = gls::chooseOrientation(false, sensor, none);
  EXPECT_EQ(atSensor.source, gls::OrientationSource::SensorPosition);
  EXPECT_NE(atSensor.reason.find("(1, 2, 3)"), std::string::npos) << atSensor.reason;
  EXPECT_EQ(gls::chooseOrientation(false, nullptr, none).source, gls::OrientationSource::MinimumSpanningTree);

  // 1,000 lidar points: an airborne swath (angles of -20 to 20 degrees), or one of its signs alone, against a
  // terrestrial scan's export (angles 0, one return, unclassified) and a few stray values.
  const std::size_t n = 1000;
  const auto decide = [&](float angle, float angleSpread, std::uint8_t returns, std::uint8_t cls, std::size_t marked) {
    std::vector<float> a(n);
    std::vector<std::uint8_t> r(n, 1), k(n, 1);
    for (std::size_t i = 0; i < n; ++i)
    {
      a[i] = angle + angleSpread * static_cast<float>(static_cast<double>(i) / n - 0.5);
      if (i < marked)
      {
        r[i] = returns;
        k[i] = cls;
      }
    }
    gls::LidarEvidence e;
    gls::countLidarEvidence(a.data(), r.data(), k.data(), nullptr, n, e);
    return gls::chooseOrientation(false, nullptr, e);
  };
  const gls::OrientationChoice swath = decide(0.0f, 40.0f, 1, 1, 0);
  EXPECT_EQ(swath.source, gls::OrientationSource::Airborne) << swath.reason;
  EXPECT_NE(swath.reason.find("scan angles recorded at"), std::string::npos) << swath.reason;
  EXPECT_EQ(decide(0.0f, 0.0f, 3, 1, 20).source, gls::OrientationSource::Airborne);  // 2% multiple returns
  EXPECT_EQ(decide(0.0f, 0.0f, 1, 2, 400).source, gls::OrientationSource::Airborne); // 40% ground
  EXPECT_EQ(decide(15.0f, 0.0f, 1, 1, 0).source, gls::OrientationSource::Airborne);  // one angle, off nadir
  const gls::OrientationChoice room = decide(0.0f, 0.0f, 1, 1, 0);
  EXPECT_EQ(room.source, gls::OrientationSource::Terrestrial) << room.reason;
  EXPECT_EQ(decide(0.0f, 0.0f, 3, 2, 5).source, gls::OrientationSource::Terrestrial); // 0.5%: stray values
  EXPECT_EQ(decide(0.0f, 360.0f, 1, 1, 0).source, gls::OrientationSource::Terrestrial); // a turning scanner's angles
  // Points left out (the finite flags) are not counted.
  std::vector<float> a(n, 20.0f);
  std::vector<unsigned char> finite(n, 0);
  gls::LidarEvidence e;
  gls::countLidarEvidence(a.data(), nullptr, nullptr, finite.data(), n, e);
  EXPECT_EQ(e.points, 0.0);
  EXPECT_EQ(gls::chooseOrientation(false, nullptr, e).source, gls::OrientationSource::Terrestrial);
}

TEST(NormalEstimation, ARealRangeScanFacesItsScannerByDefault)
{
  // The Stanford bunny's raw range scan bun045 (40,097 points on scan lines, in the scanner's frame: it looked along
  // -z from the +z side, so a normal facing it has n_z > 0 almost everywhere). The default orientation must not turn
  // a patch of scan lines over: at most 0.1% of the defined normals the wrong way (Open3D's consistent tangent-plane
  // orientation, 16 nearest for the normals and a graph of 10: 0.002%, one point).
  std::FILE* file = std::fopen(dataFile("stanford-bunny-scan045.xyz").c_str(), "r");
  ASSERT_NE(file, nullptr);
  std::vector<double> xyz;
  double p[3];
  while (std::fscanf(file, "%lf %lf %lf", &p[0], &p[1], &p[2]) == 3)
  {
    xyz.insert(xyz.end(), p, p + 3);
  }
  std::fclose(file);
  const std::size_t n = xyz.size() / 3;
  ASSERT_EQ(n, 40097u);
  gls::NormalEstimationSettings s;
  gls::NormalEstimationResult r;
  ASSERT_TRUE(gls::estimateNormals(xyz.data(), n, s, r));
  std::size_t defined = 0, away = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (std::isfinite(r.normals[3 * i + 2]))
    {
      ++defined;
      away += r.normals[3 * i + 2] < 0.0 ? 1 : 0;
    }
  }
  std::printf("range scan bun045: %zu of %zu normals defined, %zu facing away from the scanner (%.3f%%)\n", defined, n,
    away, 100.0 * static_cast<double>(away) / static_cast<double>(defined));
  EXPECT_GE(defined, n - n / 1000);
  EXPECT_LE(static_cast<double>(away), 0.001 * static_cast<double>(defined));
}
