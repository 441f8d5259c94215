// Ball and k-nearest queries of the grid against brute force on seeded random clouds.
#include "gls/NeighborGrid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

namespace
{

std::vector<double> randomCloud(std::size_t n, unsigned seed, double sx, double sy, double sz)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> xyz(3 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    xyz[3 * i] = sx * u(rng);
    xyz[3 * i + 1] = sy * u(rng);
    xyz[3 * i + 2] = sz * u(rng);
  }
  return xyz;
}

double dist2(const std::vector<double>& xyz, std::size_t i, const gls::Vec3& c)
{
  const double dx = xyz[3 * i] - c.x, dy = xyz[3 * i + 1] - c.y, dz = xyz[3 * i + 2] - c.z;
  return dx * dx + dy * dy + dz * dz;
}

} // namespace

TEST(NeighborGrid, BallQueryMatchesBruteForce)
{
  for (double cell : { 0.05, 0.2, 3.0 })
  {
    const std::vector<double> xyz = randomCloud(3000, 1, 1.0, 2.0, 0.3);
    gls::NeighborGrid grid;
    grid.build(xyz.data(), nullptr, 3000, cell);
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> u(-0.5, 2.5);
    for (int q = 0; q < 50; ++q)
    {
      const gls::Vec3 c{ u(rng), u(rng), u(rng) * 0.2 };
      const double r = 0.02 + 0.3 * (q % 5);
      std::vector<std::uint64_t> found;
      gls::forEachInBall(grid.view(), c, r, [&](std::uint64_t s, const gls::Vec3&, double) {
        found.push_back(grid.view().ids[s]);
      });
      std::vector<std::uint64_t> expected;
      for (std::size_t i = 0; i < 3000; ++i)
      {
        if (dist2(xyz, i, c) < r * r)
        {
          expected.push_back(i);
        }
      }
      std::sort(found.begin(), found.end());
      ASSERT_EQ(found, expected) << "cell " << cell << " query " << q;
    }
  }
}

TEST(NeighborGrid, BallQueryMatchesBruteForceFarFromTheOriginAndOnCellBounds)
{
  // Rows are narrowed to the ball's chord (blockRow): check it leaves no point out where rounding is worst, with
  // coordinates of 1e6 and radii of a few cells, centres on cell corners, and points on the sphere itself.
  const double offset = 1.0e6, cell = 0.01;
  std::vector<double> xyz = randomCloud(20000, 5, 0.3, 0.3, 0.3);
  for (double& v : xyz)
  {
    v += offset;
  }
  gls::NeighborGrid grid;
  grid.build(xyz.data(), nullptr, 20000, cell);
  const gls::GridView& g = grid.view();
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(0.0, 0.3);
  for (int q = 0; q < 300; ++q)
  {
    gls::Vec3 c{ offset + u(rng), offset + u(rng), offset + u(rng) };
    if (q % 3 == 0) // a cell corner
    {
      c = { g.origin.x + 7 * g.cellSize, g.origin.y + 11 * g.cellSize, g.origin.z + 13 * g.cellSize };
    }
    const double r = (q % 3 == 1) ? std::sqrt(dist2(xyz, q, c)) : 0.003 + 0.01 * (q % 7);
    std::vector<std::uint64_t> found;
    gls::forEachInBall(g, c, r, [&](std::uint64_t s, const gls::Vec3&, double) { found.push_back(g.ids[s]); });
    std::vector<std::uint64_t> expected;
    for (std::size_t i = 0; i < 20000; ++i)
    {
      const double dx = xyz[3 * i] - c.x, dy = xyz[3 * i + 1] - c.y, dz = xyz[3 * i + 2] - c.z;
      if (dx * dx + dy * dy + dz * dz < r * r)
      {
        expected.push_back(i);
      }
    }
    std::sort(found.begin(), found.end());
    ASSERT_EQ(found, expected) << "query " << q;
  }
}

TEST(NeighborGrid, KNearestMatchesBruteForce)
{
  const std::vector<double> xyz = randomCloud(2000, 3, 5.0, 1.0, 0.01);
  gls::NeighborGrid grid;
  grid.build(xyz.data(), nullptr, 2000, gls::NeighborGrid::suggestCellSizeForKNearest(xyz.data(), 2000, 16));
  std::vector<std::pair<double, std::uint64_t>> out;
  for (std::size_t q = 0; q < 2000; q += 37)
  {
    const gls::Vec3 c{ xyz[3 * q], xyz[3 * q + 1], xyz[3 * q + 2] };
    for (int k : { 1, 16, 40 })
    {
      grid.kNearest(c, k, out);
      std::vector<std::pair<double, std::uint64_t>> all;
      for (std::size_t i = 0; i < 2000; ++i)
      {
        all.emplace_back(dist2(xyz, i, c), i);
      }
      std::sort(all.begin(), all.end());
      ASSERT_EQ(out.size(), static_cast<std::size_t>(k));
      for (int j = 0; j < k; ++j)
      {
        EXPECT_EQ(grid.view().ids[out[j].second], all[j].second);
        EXPECT_EQ(out[j].first, all[j].first);
      }
    }
  }
  // A query outside the cloud and a k larger than the cloud.
  grid.kNearest({ -10.0, 30.0, 5.0 }, 5000, out);
  EXPECT_EQ(out.size(), 2000u);
}

TEST(NeighborGrid, KNearestBreaksTiesByOriginalIndexAndHonoursTheMask)
{
  // A lattice (many equal distances) with repeated points, in a shuffled order, queried at lattice points, between
  // them and outside, on several cell sizes (the pruned cells and rows must never drop a tie).
  std::vector<double> xyz;
  for (int z = 0; z < 4; ++z)
    for (int y = 0; y < 9; ++y)
      for (int x = 0; x < 9; ++x)
      {
        xyz.insert(xyz.end(), { 0.1 * x, 0.1 * y, 0.1 * z });
        if ((x + y + z) % 7 == 0)
        {
          xyz.insert(xyz.end(), { 0.1 * x, 0.1 * y, 0.1 * z }); // a repeated point
        }
      }
  const std::size_t n = xyz.size() / 3;
  std::mt19937_64 rng(7);
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    order[i] = i;
  }
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<double> shuffled(3 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    std::copy(&xyz[3 * order[i]], &xyz[3 * order[i]] + 3, &shuffled[3 * i]);
  }
  std::vector<unsigned char> keep(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    keep[i] = i % 3 != 1;
  }
  for (double cell : { 0.03, 0.1, 0.25, 2.0 })
  {
    gls::NeighborGrid grid;
    grid.build(shuffled.data(), nullptr, n, cell);
    const gls::GridView& g = grid.view();
    std::vector<unsigned char> keepSorted(g.count);
    for (std::size_t s = 0; s < g.count; ++s)
    {
      keepSorted[s] = keep[g.ids[s]];
    }
    std::vector<std::pair<double, std::uint64_t>> out;
    for (const gls::Vec3 c : { gls::Vec3{ 0.4, 0.4, 0.1 }, gls::Vec3{ 0.45, 0.35, 0.15 }, gls::Vec3{ 0.0, 0.8, 0.3 },
           gls::Vec3{ -0.5, 0.2, 2.0 } })
    {
      for (int k : { 1, 6, 7, 27, 60 })
      {
        for (bool masked : { false, true })
        {
          grid.kNearest(c, k, out, masked ? keepSorted.data() : nullptr);
          std::vector<std::pair<double, std::uint64_t>> all;
          for (std::size_t i = 0; i < n; ++i)
          {
            if (!masked || keep[i])
            {
              all.emplace_back(dist2(shuffled, i, c), i);
            }
          }
          std::sort(all.begin(), all.end());
          ASSERT_EQ(out.size(), std::min<std::size_t>(k, all.size()));
          for (std::size_t j = 0; j < out.size(); ++j)
          {
            ASSERT_EQ(g.ids[out[j].second], all[j].second) << "cell " << cell << " k " << k << " rank " << j;
            ASSERT_EQ(out[j].first, all[j].first);
          }
        }
      }
    }
  }
}

TEST(NeighborGrid, KNearestOfACellRunIsKNearestBitForBit)
{
  // The queries of a run of one cell's points answered together must give what one query at a time gives: on a
  // flat random cloud (cells suited to k = 16), a lattice with repeated points (ties) on cells smaller than its
  // spacing (the gathered cells then never hold the answer), about its spacing and holding it whole, and far from the
  // origin; runs cut short at arbitrary points, k from 0 to more than the cloud holds.
  std::vector<std::vector<double>> clouds{ randomCloud(1500, 11, 5.0, 1.0, 0.01) };
  std::vector<double> lattice;
  for (int z = 0; z < 4; ++z)
    for (int y = 0; y < 9; ++y)
      for (int x = 0; x < 9; ++x)
      {
        for (int copies = (x + y + z) % 7 == 0 ? 2 : 1; copies > 0; --copies)
        {
          lattice.insert(lattice.end(), { 0.1 * x, 0.1 * y, 0.1 * z });
        }
      }
  clouds.push_back(lattice);
  std::vector<double> far = randomCloud(800, 12, 2.0, 2.0, 2.0);
  for (std::size_t i = 0; i < far.size(); i += 3)
  {
    far[i] += 1e6;
  }
  clouds.push_back(far);
  for (const std::vector<double>& xyz : clouds)
  {
    const std::size_t n = xyz.size() / 3;
    for (double cell : { 0.03, 0.1, 0.25, gls::NeighborGrid::suggestCellSizeForKNearest(xyz.data(), n, 16), 50.0 })
    {
      gls::NeighborGrid grid;
      grid.build(xyz.data(), nullptr, n, cell);
      const gls::GridView& g = grid.view();
      gls::NeighborGrid::CellRunScratch scratch;
      std::vector<std::pair<double, std::uint64_t>> single;
      for (int k : { 0, 1, 6, 16, 60, static_cast<int>(n) + 3 })
      {
        if (k > 60 && n > 500)
        {
          continue; // more than the cloud holds: on the lattice only (each query then sorts the whole cloud)
        }
        std::size_t answered = 0;
        for (std::uint64_t s = 0; s < g.count;)
        {
          const std::uint64_t end = std::min<std::uint64_t>(grid.cellRunEnd(s), s + 1 + (s * 7) % 13);
          ASSERT_GT(end, s);
          std::uint64_t next = s;
          grid.kNearestOfCellRun(s, end, k, scratch,
            [&](std::uint64_t q, const std::vector<std::pair<double, std::uint64_t>>& together) {
              ASSERT_EQ(q, next++); // each point of the run once, in order
              grid.kNearest(g.points[q], k, single);
              ASSERT_EQ(together.size(), single.size()) << "cell " << cell << " k " << k << " query " << q;
              for (std::size_t j = 0; j < single.size(); ++j)
              {
                ASSERT_EQ(together[j].second, single[j].second) << "cell " << cell << " k " << k << " rank " << j;
                ASSERT_EQ(together[j].first, single[j].first);
              }
            });
          ASSERT_EQ(next, end);
          answered += end - s;
          s = end;
        }
        EXPECT_EQ(answered, g.count);
      }
    }
  }
}

TEST(NeighborGrid, KNearestOnThinGridsWithFewerAdmittedPointsThanAsked)
{
  // Points along one axis with a tiny cell size: the grid is 1 x 1 x ~65000 cells (or 1 x ~65000 x 1, ~65000 x 1 x 1)
  // and a masked query admitting 5 points of 300 must walk to the grid's far end in rings that each cost O(1) (it
  // took O(R^2) row visits a query before: minutes for these queries).
  for (int axis = 0; axis < 3; ++axis)
  {
    std::vector<double> xyz(3 * 300, 0.0);
    for (int i = 0; i < 300; ++i)
    {
      xyz[3 * i + axis] = std::pow(i / 299.0, 3.0); // crowded at one end
    }
    gls::NeighborGrid grid;
    grid.build(xyz.data(), nullptr, 300, 1e-9);
    const gls::GridView& g = grid.view();
    ASSERT_GT(g.dims[axis], 60000);
    std::vector<unsigned char> admit(g.count, 0);
    for (std::size_t s = 0; s < g.count; ++s)
    {
      admit[s] = g.ids[s] % 60 == 7;
    }
    std::vector<std::pair<double, std::uint64_t>> out;
    for (std::size_t q : { 0u, 150u, 299u })
    {
      const gls::Vec3 c{ xyz[3 * q], xyz[3 * q + 1], xyz[3 * q + 2] };
      grid.kNearest(c, 40, out, admit.data());
      std::vector<std::pair<double, std::uint64_t>> all;
      for (std::size_t i = 7; i < 300; i += 60)
      {
        all.emplace_back(dist2(xyz, i, c), i);
      }
      std::sort(all.begin(), all.end());
      ASSERT_EQ(out.size(), all.size()) << axis;
      for (std::size_t j = 0; j < out.size(); ++j)
      {
        ASSERT_EQ(g.ids[out[j].second], all[j].second) << axis;
      }
    }
  }
}

TEST(NeighborGrid, LeavesOutNonFinitePointsAndMaskedPoints)
{
  std::vector<double> xyz = { 0, 0, 0, 1, 0, 0, std::nan(""), 0, 0, 0, 1, 0, 0, 0, INFINITY };
  const unsigned char mask[] = { 1, 0, 1, 1, 1 };
  gls::NeighborGrid grid;
  grid.build(xyz.data(), nullptr, 5, 0.5, mask);
  EXPECT_EQ(grid.view().count, 2u);
  std::vector<std::uint64_t> found;
  gls::forEachInBall(grid.view(), { 0, 0, 0 }, 10.0, [&](std::uint64_t s, const gls::Vec3&, double) {
    found.push_back(grid.view().ids[s]);
  });
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found, (std::vector<std::uint64_t>{ 0, 3 }));
}

TEST(NeighborGrid, HugeExtentWithTinyCellsStaysBounded)
{
  // A cloud 1e6 times longer than wide with a tiny requested cell: the cell count is capped.
  std::vector<double> xyz = randomCloud(1000, 4, 1e6, 1.0, 1.0);
  gls::NeighborGrid grid;
  grid.build(xyz.data(), nullptr, 1000, 1e-3);
  const auto& g = grid.view();
  EXPECT_LE(static_cast<double>(g.dims[0]) * g.dims[1] * g.dims[2], 65536.0 * 1.05);
  std::size_t n = 0;
  gls::forEachInBall(g, { 5e5, 0.5, 0.5 }, 2e6, [&](std::uint64_t, const gls::Vec3&, double) { ++n; });
  EXPECT_EQ(n, 1000u);
}

TEST(NeighborGrid, OverflowingExtentFallsBackToOneCell)
{
  // Finite points whose extent overflows a double: one cell, correct queries, no hang.
  const std::vector<double> xyz = { -1e308, 0, 0, 1e308, 0, 0, 0, 0, 0, 1, 0, 0 };
  gls::NeighborGrid grid;
  grid.build(xyz.data(), nullptr, 4, 0.5);
  EXPECT_EQ(grid.view().dims[0] * grid.view().dims[1] * grid.view().dims[2], 1);
  std::vector<std::uint64_t> found;
  gls::forEachInBall(grid.view(), { 0.2, 0, 0 }, 2.0, [&](std::uint64_t s, const gls::Vec3&, double) {
    found.push_back(grid.view().ids[s]);
  });
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found, (std::vector<std::uint64_t>{ 2, 3 }));
  std::vector<std::pair<double, std::uint64_t>> knn;
  grid.kNearest({ 0.9, 0, 0 }, 2, knn);
  ASSERT_EQ(knn.size(), 2u);
  EXPECT_EQ(grid.view().ids[knn[0].second], 3u);
}

TEST(NeighborGrid, AdmitRuleIsTheSameWithAndWithoutTheNormalizedCopy)
{
  // admitOrientedPoints and unitNormal (the multi-resolution pyramid's way) against normalizeAndAdmit: the same flags
  // and the same bits, for normals of every kind (unit, long, tiny, zero, subnormal, overflowing, inf, NaN) and points
  // finite or not, on 1 and 3 threads.
  const double inf = INFINITY, nan = NAN;
  const double kinds[][3] = { { 0, 0, 1 }, { 3, -4, 12 }, { 1e-3, 2e-3, -5e-4 }, { 0, 0, 0 }, { 1e-310, 0, 0 },
    { 1e200, 1e200, 0 }, { inf, 0, 0 }, { nan, 1, 0 }, { -0.0, 0.6, 0.8 } };
  const double places[][3] = { { 0.5, -2, 3 }, { nan, 0, 0 }, { 0, inf, 0 } };
  std::vector<double> points, normals;
  for (const auto& m : kinds)
  {
    for (const auto& p : places)
    {
      points.insert(points.end(), p, p + 3);
      normals.insert(normals.end(), m, m + 3);
    }
  }
  const std::size_t n = points.size() / 3;
  std::vector<double> unit;
  std::vector<unsigned char> admit;
  gls::normalizeAndAdmit(points.data(), normals.data(), n, unit, admit);
  EXPECT_EQ(std::count(admit.begin(), admit.end(), 1), 4); // the four normalizable normals at the finite point
  for (int threads : { 1, 3 })
  {
    std::vector<unsigned char> flags(n, 7);
    gls::admitOrientedPoints(points.data(), normals.data(), n, flags.data(), threads);
    EXPECT_EQ(flags, admit);
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    double u[3];
    EXPECT_EQ(gls::unitNormal(&normals[3 * i], u), !std::isnan(unit[3 * i])) << i;
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_EQ(std::memcmp(&u[a], &unit[3 * i + a], sizeof(double)), 0) << i;
    }
  }
}

TEST(NeighborGrid, ASparseCellIndexAnswersAsADenseOne)
{
  // A sphere and a plane across it, in cells far smaller than the cloud: 8 cells a point (the most a grid takes), so
  // the grid keeps only its occupied cells (the sparse index). A NaN point and a masked point stay out.
  std::mt19937_64 rng(11);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::size_t n = 20000;
  std::vector<double> xyz;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (i % 2 == 0)
    {
      const double x = gauss(rng), y = gauss(rng), z = gauss(rng);
      const double r = std::sqrt(x * x + y * y + z * z);
      xyz.insert(xyz.end(), { x / r, y / r, z / r });
    }
    else
    {
      xyz.insert(xyz.end(), { u(rng), u(rng), 0.3 }); // whole rows of occupied cells
    }
  }
  xyz[3 * 5] = std::nan("");
  std::vector<unsigned char> include(n, 1);
  include[7] = 0;
  gls::NeighborGrid grid;
  grid.build(xyz.data(), nullptr, n, 0.02, include.data());
  const gls::GridView& g = grid.view();
  ASSERT_EQ(g.cellStart, nullptr);
  ASSERT_NE(g.rowEntry, nullptr);
  ASSERT_EQ(g.count, n - 2);
  // The index: the first point of every cell (and of every row's end) is the number of points in the cells before.
  std::vector<std::int64_t> keys(g.count);
  for (std::size_t s = 0; s < g.count; ++s)
  {
    const gls::Vec3& p = g.points[s];
    keys[s] = (gls::gridCellOf(g, p.z, 2) * g.dims[1] + gls::gridCellOf(g, p.y, 1)) * g.dims[0] +
      gls::gridCellOf(g, p.x, 0);
  }
  ASSERT_TRUE(std::is_sorted(keys.begin(), keys.end()));
  std::size_t checked = 0;
  for (std::int64_t row = 0; row < g.dims[1] * g.dims[2]; ++row)
  {
    for (std::int64_t x = 0; x <= g.dims[0]; ++x)
    {
      const auto before = std::lower_bound(keys.begin(), keys.end(), row * g.dims[0] + x) - keys.begin();
      ASSERT_EQ(gls::gridCellStart(g, row, x), static_cast<std::uint64_t>(before)) << "row " << row << " x " << x;
      ++checked;
    }
  }
  EXPECT_GT(checked, 2 * n + 65536); // more cells than a dense index is kept for
  // Ball and k-nearest queries against brute force.
  std::vector<std::pair<double, std::uint64_t>> out;
  for (std::size_t q = 0; q < n; q += 331)
  {
    const gls::Vec3 c{ std::isfinite(xyz[3 * q]) ? xyz[3 * q] : 0.1, xyz[3 * q + 1], xyz[3 * q + 2] };
    std::vector<std::pair<double, std::uint64_t>> all;
    for (std::size_t i = 0; i < n; ++i)
    {
      if (include[i] && std::isfinite(xyz[3 * i]))
      {
        all.emplace_back(dist2(xyz, i, c), i);
      }
    }
    std::sort(all.begin(), all.end());
    for (double r : { 0.03, 0.15 })
    {
      std::vector<std::uint64_t> inBall, expected;
      gls::forEachInBall(g, c, r, [&](std::uint64_t s, const gls::Vec3&, double) { inBall.push_back(g.ids[s]); });
      for (const auto& a : all)
      {
        if (a.first < r * r)
        {
          expected.push_back(a.second);
        }
      }
      std::sort(inBall.begin(), inBall.end());
      std::sort(expected.begin(), expected.end());
      EXPECT_EQ(inBall, expected);
    }
    grid.kNearest(c, 16, out);
    ASSERT_EQ(out.size(), 16u);
    for (int j = 0; j < 16; ++j)
    {
      EXPECT_EQ(g.ids[out[j].second], all[j].second);
    }
  }
}
