// Coincident points (gls/CoincidentPoints.h) against a brute-force oracle: every point's group is that of the first
// earlier point at bitwise-equal coordinates (-0 equal to +0), non-finite points alone, groups numbered in input order.
#include "gls/CoincidentPoints.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <set>

namespace
{

/// The first point (input order) at i's coordinates; i itself for a non-finite point. O(n^2).
std::vector<std::uint64_t> firstCopiesByBruteForce(const std::vector<double>& xyz)
{
  const std::size_t n = xyz.size() / 3;
  const auto finite = [&](std::size_t i) {
    return std::isfinite(xyz[3 * i]) && std::isfinite(xyz[3 * i + 1]) && std::isfinite(xyz[3 * i + 2]);
  };
  std::vector<std::uint64_t> first(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    first[i] = i;
    for (std::size_t j = 0; finite(i) && j < i; ++j)
    {
      if (finite(j) && xyz[3 * j] == xyz[3 * i] && xyz[3 * j + 1] == xyz[3 * i + 1] && xyz[3 * j + 2] == xyz[3 * i + 2])
      {
        first[i] = j;
        break;
      }
    }
  }
  return first;
}

/// Checks c against the oracle: the groups, their numbering in input order and each group's copies in input order.
void expectMatchesOracle(const std::vector<double>& xyz, const gls::CoincidentPoints& c)
{
  const std::vector<std::uint64_t> first = firstCopiesByBruteForce(xyz);
  const std::size_t n = first.size();
  ASSERT_EQ(c.representative.size(), n);
  gls::PointIndices distinct;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (first[i] == i)
    {
      distinct.push_back(i);
    }
  }
  ASSERT_EQ(c.distinct, distinct);
  ASSERT_EQ(c.copyStart.size(), distinct.size() + 1);
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::uint64_t u = c.representative[i];
    ASSERT_LT(u, distinct.size());
    ASSERT_EQ(c.distinct[u], first[i]) << "point " << i;
  }
  for (std::size_t u = 0; u < distinct.size(); ++u)
  {
    for (std::uint64_t k = c.copyStart[u]; k < c.copyStart[u + 1]; ++k)
    {
      ASSERT_EQ(c.representative[c.copies[k]], u);
      if (k > c.copyStart[u])
      {
        ASSERT_LT(c.copies[k - 1], c.copies[k]); // input order within a group
      }
    }
  }
  EXPECT_EQ(c.copyStart.back(), n);
}

} // namespace

TEST(CoincidentPoints, MatchBruteForceWithCopiesSignedZerosAndNonFinitePoints)
{
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> lattice(-6, 6); // a coarse lattice: many exact coincidences by chance
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const std::size_t n = 4000;
  std::vector<double> xyz(3 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    double* p = &xyz[3 * i];
    const unsigned kind = static_cast<unsigned>(rng() % 10);
    if (kind == 0 && i > 0)
    {
      const double* q = &xyz[3 * (rng() % i)]; // a copy of an earlier point, its zeros' signs flipped
      for (int k = 0; k < 3; ++k)
      {
        p[k] = q[k] == 0.0 ? -q[k] : q[k];
      }
    }
    else if (kind == 1)
    {
      p[0] = (rng() % 2) ? nan : inf; // never merged, even with an equal copy
      p[1] = 0.0;
      p[2] = 0.0;
    }
    else
    {
      for (int k = 0; k < 3; ++k)
      {
        p[k] = 0.5 * lattice(rng);
      }
    }
  }
  const gls::CoincidentPoints c = gls::findCoincidentPoints(xyz.data(), n);
  expectMatchesOracle(xyz, c);
  EXPECT_GT(c.merged(), n / 3); // the lattice has 2,197 sites for 3,600 finite points: many share theirs
}

TEST(CoincidentPoints, OnePositionRepeatedIsOneGroupInInputOrder)
{
  std::vector<double> xyz;
  for (int i = 0; i < 1000; ++i)
  {
    xyz.insert(xyz.end(), { 1.25, (i % 2) ? -0.0 : 0.0, -3.0 });
  }
  const gls::CoincidentPoints c = gls::findCoincidentPoints(xyz.data(), 1000);
  expectMatchesOracle(xyz, c);
  EXPECT_EQ(c.distinct.size(), 1u);
  EXPECT_EQ(c.merged(), 999u);
}

TEST(CoincidentPoints, DistinctPointsStayDistinct)
{
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> xyz(3 * 5000);
  for (double& v : xyz)
  {
    v = u(rng);
  }
  const gls::CoincidentPoints c = gls::findCoincidentPoints(xyz.data(), 5000);
  expectMatchesOracle(xyz, c);
  EXPECT_EQ(c.merged(), 0u);
}

TEST(CoincidentPoints, SameGroupsForAnyThreadCount)
{
  // Enough points for the sort to run in slices (sortByKey: 65,536 or more), copies and non-finite points
  // among them: every thread count gives the one-thread result, whose merged count a set of the positions confirms.
  std::mt19937_64 rng(23);
  std::uniform_int_distribution<int> lattice(-40, 40);
  const double inf = std::numeric_limits<double>::infinity();
  const std::size_t n = 100000;
  std::vector<double> xyz(3 * n);
  std::set<std::array<double, 3>> sites;
  std::size_t nonFinite = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    double* p = &xyz[3 * i];
    if (rng() % 50 == 0)
    {
      p[0] = inf;
      p[1] = p[2] = 0.0;
      ++nonFinite;
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      p[k] = 0.25 * lattice(rng);
    }
    sites.insert({ p[0] + 0.0, p[1] + 0.0, p[2] + 0.0 });
  }
  const gls::CoincidentPoints one = gls::findCoincidentPoints(xyz.data(), n, 1);
  EXPECT_EQ(one.distinct.size(), sites.size() + nonFinite);
  EXPECT_GT(one.merged(), 0u);
  for (int threads : { 2, 3, 5 })
  {
    const gls::CoincidentPoints c = gls::findCoincidentPoints(xyz.data(), n, threads);
    EXPECT_EQ(c.representative, one.representative) << threads << " threads";
    EXPECT_EQ(c.distinct, one.distinct) << threads << " threads";
    EXPECT_EQ(c.copyStart, one.copyStart) << threads << " threads";
    EXPECT_EQ(c.copies, one.copies) << threads << " threads";
  }
  // Distinct points take the path without groups: the same structure as the grouping path gives.
  std::vector<double> spread(3 * n);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double& v : spread)
  {
    v = u(rng);
  }
  const gls::CoincidentPoints d = gls::findCoincidentPoints(spread.data(), n, 2);
  EXPECT_EQ(d.merged(), 0u);
  ASSERT_EQ(d.copyStart.size(), n + 1);
  for (std::size_t i = 0; i < n; ++i)
  {
    ASSERT_EQ(d.representative[i], i);
    ASSERT_EQ(d.distinct[i], i);
    ASSERT_EQ(d.copies[i], i);
    ASSERT_EQ(d.copyStart[i + 1], i + 1);
  }
}
