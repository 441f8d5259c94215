// The moment sets (MomentSet.h: the oriented sphere's, the filters' fit; ShapeOperator.h: the principal curvatures'):
// every rule a fitted value declares, checked for every value of every set against its point rule summed over the
// points one by one. A value added to a set, or a set added to the list, is checked here with no new test: its move of
// origin, its sums over a cell and their gradient, the merge of its cell statistics; and the sphere's moments in the
// one pass's and the multi-resolution layouts, and the curvature set's move of its weighted sums.
#include "gls/AggregateMoments.h"
#include "gls/CellMoments.h"
#include "gls/MomentBins.h"
#include "gls/MomentSet.h"
#include "gls/ShapeOperator.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace
{

/// The sums of every value of a set.
template <typename Set>
using Values = std::array<double, Set::kValues>;

struct Points
{
  std::vector<gls::Vec3> positions, normals;
};

/// n points in a cube of edge h at `centre`, with unit normals near +z (a patch of a surface).
Points cubeOfPoints(std::size_t n, const gls::Vec3& centre, double h, unsigned seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  Points p;
  for (std::size_t i = 0; i < n; ++i)
  {
    p.positions.push_back(centre + gls::Vec3{ h * u(rng), h * u(rng), h * u(rng) });
    const gls::Vec3 n0{ 0.4 * u(rng), 0.4 * u(rng), 1.0 };
    p.normals.push_back((1.0 / std::sqrt(gls::squaredNorm(n0))) * n0);
  }
  return p;
}

/// sum over the points of weight(i) f(q_i - o, n_i).
template <typename Set, typename Weight>
Values<Set> summedValues(const Points& p, const gls::Vec3& o, Weight&& weight)
{
  Values<Set> sum{};
  for (std::size_t i = 0; i < p.positions.size(); ++i)
  {
    const gls::Vec3 x = p.positions[i] - o;
    double f[Set::kValues];
    Set::pointValues(x, gls::squaredNorm(x), p.normals[i], f);
    for (int j = 0; j < Set::kValues; ++j)
    {
      sum[j] += weight(i) * f[j];
    }
  }
  return sum;
}

/// The cell statistics of the points, formed point by point (addPointToCell) about their centroid.
template <typename Set>
typename Set::Cell cellOf(const Points& p)
{
  typename Set::Cell cell{};
  for (std::size_t i = 0; i < p.positions.size(); ++i)
  {
    cell.count += 1.0;
    cell.centroid = cell.centroid + p.positions[i];
    cell.normalSum = cell.normalSum + p.normals[i];
  }
  cell.centroid = (1.0 / cell.count) * cell.centroid;
  for (std::size_t i = 0; i < p.positions.size(); ++i)
  {
    Set::addPointToCell(cell, p.positions[i] - cell.centroid, p.normals[i]);
  }
  return cell;
}

template <std::size_t V>
void expectValuesNear(const std::array<double, V>& got, const std::array<double, V>& want, double tolerance,
  const char* what)
{
  for (std::size_t j = 0; j < V; ++j)
  {
    EXPECT_NEAR(got[j], want[j], tolerance * (1.0 + std::abs(want[j]))) << what << ", value " << j;
  }
}

const gls::Vec3 kCentre{ 0.3, -0.2, 0.5 };
const gls::Vec3 kOrigin{ -0.1, 0.25, 0.05 };

/// The rules' tests, for every set.
template <typename Set>
class MomentSetRules : public ::testing::Test
{
};
using Sets = ::testing::Types<gls::OrientedSphereMoments, gls::ShapeOperatorMoments>;
TYPED_TEST_SUITE(MomentSetRules, Sets);

} // namespace

TYPED_TEST(MomentSetRules, ShiftMovesEveryValuesSumsToAnotherOrigin)
{
  using Set = TypeParam;
  // Sums about o, weighted (any weight per point, the same for its values), moved to p: the sums about p.
  const Points pts = cubeOfPoints(200, kCentre, 0.4, 1);
  const auto weight = [](std::size_t i) { return 0.5 + 0.01 * static_cast<double>(i % 17); };
  const gls::Vec3 p{ 0.7, 0.1, -0.3 };
  Values<Set> moved = summedValues<Set>(pts, kOrigin, weight);
  const gls::Vec3 u = kOrigin - p;
  Set::shiftValues(u, gls::squaredNorm(u), moved.data());
  expectValuesNear(moved, summedValues<Set>(pts, p, weight), 1e-12, "shiftValues");
}

TYPED_TEST(MomentSetRules, CellValuesAreTheSumsOfTheCellsPointsAndTheirGradient)
{
  using Set = TypeParam;
  // F = sum f(q_i - o, n_i) and H = sum (a . y_i) f(q_i - o, n_i) from the cell's statistics alone.
  const Points pts = cubeOfPoints(300, kCentre, 0.2, 2);
  const typename Set::Cell cell = cellOf<Set>(pts);
  const gls::Vec3 a{ 0.6, -0.8, 0.3 };
  Values<Set> F{}, H{};
  Set::cellValues(cell, cell.centroid - kOrigin, a, F.data(), H.data());
  expectValuesNear(F, summedValues<Set>(pts, kOrigin, [](std::size_t) { return 1.0; }), 1e-12, "F");
  const auto along = [&](std::size_t i) { return gls::dot(a, pts.positions[i] - cell.centroid); };
  expectValuesNear(H, summedValues<Set>(pts, kOrigin, along), 1e-12, "H");
  EXPECT_EQ(H[gls::kOne], 0.0);
}

TYPED_TEST(MomentSetRules, MergedCellStatisticsGiveTheSameValuesAsThePoints)
{
  using Set = TypeParam;
  // A parent formed from two children (addChildToCell) gives every value's F and H of all their points.
  const Points left = cubeOfPoints(150, kCentre, 0.1, 3);
  const Points right = cubeOfPoints(90, kCentre + gls::Vec3{ 0.1, 0.02, -0.03 }, 0.1, 4);
  Points both = left;
  both.positions.insert(both.positions.end(), right.positions.begin(), right.positions.end());
  both.normals.insert(both.normals.end(), right.normals.begin(), right.normals.end());
  const typename Set::Cell children[2] = { cellOf<Set>(left), cellOf<Set>(right) };
  typename Set::Cell parent{};
  parent.count = children[0].count + children[1].count;
  parent.centroid = (1.0 / parent.count) * (children[0].count * children[0].centroid +
    children[1].count * children[1].centroid);
  parent.normalSum = children[0].normalSum + children[1].normalSum;
  for (const typename Set::Cell& child : children)
  {
    Set::addChildToCell(parent, child, child.centroid - parent.centroid);
  }
  const typename Set::Cell direct = cellOf<Set>(both);
  const gls::Vec3 a{ -0.2, 0.5, 0.9 };
  Values<Set> Fm{}, Hm{}, Fd{}, Hd{};
  Set::cellValues(parent, parent.centroid - kOrigin, a, Fm.data(), Hm.data());
  Set::cellValues(direct, direct.centroid - kOrigin, a, Fd.data(), Hd.data());
  expectValuesNear(Fm, Fd, 1e-12, "merged F");
  expectValuesNear(Hm, Hd, 1e-12, "merged H");
}

TEST(MomentSet, OnePassAndMultiresolutionMomentsGiveTheSameWeightedSums)
{
  using Set = gls::OrientedSphereMoments;
  // The one pass stores every value but |x|^2 (its moments are those of d^2); the multi-resolution layout stores all.
  // Both give the weighted sums and their t-derivatives of the points, as the weights summed point by point do.
  const Points pts = cubeOfPoints(400, gls::Vec3{ 0.0, 0.0, 0.0 }, 0.8, 5);
  const gls::Vec3 p{ 0.05, -0.02, 0.01 };
  const double t = 0.5;
  gls::Moments onePass;
  gls::AggregateMoments aggregate;
  gls::clearMoments(onePass);
  gls::clearMoments(aggregate);
  std::vector<double> w(pts.positions.size()), dw(pts.positions.size());
  for (std::size_t i = 0; i < pts.positions.size(); ++i)
  {
    const gls::Vec3 x = pts.positions[i] - p;
    const double d2 = gls::squaredNorm(x);
    w[i] = gls::weightAt(d2, t);
    dw[i] = gls::weightDerivativeAt(d2, t);
    if (d2 < t * t)
    {
      gls::addToMoments(onePass, x, d2, pts.normals[i]);
      gls::addPoint(aggregate, x, d2, pts.normals[i]);
    }
  }
  ASSERT_GT(gls::neighborCount(onePass), 50.0);
  EXPECT_EQ(gls::neighborCount(onePass), gls::neighborCount(aggregate));
  const Values<Set> sums = summedValues<Set>(pts, p, [&](std::size_t i) { return w[i]; });
  const Values<Set> derivatives = summedValues<Set>(pts, p, [&](std::size_t i) { return dw[i]; });
  gls::WeightedSums want, wantD;
  gls::toWeightedSums(sums.data(), derivatives.data(), want, wantD);
  for (int layout = 0; layout < 2; ++layout)
  {
    gls::WeightedSums s, ds;
    if (layout == 0)
    {
      gls::weightedSumsFromMoments(onePass, t, s, ds);
    }
    else
    {
      gls::weightedSumsFromMoments(aggregate, t, s, ds);
    }
    const double scales[2] = { want.W, wantD.W };
    const gls::WeightedSums* got[2] = { &s, &ds };
    const gls::WeightedSums* ref[2] = { &want, &wantD };
    for (int k = 0; k < 2; ++k)
    {
      const double tol = 1e-11 * std::abs(scales[k]);
      EXPECT_NEAR(got[k]->W, ref[k]->W, tol) << "layout " << layout << " derivative " << k;
      EXPECT_NEAR(got[k]->P.x, ref[k]->P.x, tol);
      EXPECT_NEAR(got[k]->P.y, ref[k]->P.y, tol);
      EXPECT_NEAR(got[k]->P.z, ref[k]->P.z, tol);
      EXPECT_NEAR(got[k]->N.x, ref[k]->N.x, tol);
      EXPECT_NEAR(got[k]->N.y, ref[k]->N.y, tol);
      EXPECT_NEAR(got[k]->N.z, ref[k]->N.z, tol);
      EXPECT_NEAR(got[k]->PN, ref[k]->PN, tol);
      EXPECT_NEAR(got[k]->PP, ref[k]->PP, tol);
    }
  }
}

TEST(MomentSet, TheCurvatureSetMovesItsWeightedSumsAsTheSumsAboutThePoint)
{
  using Set = gls::ShapeOperatorMoments;
  // The CPU multi-resolution kernel keeps its sums about a corner o and, for each scale, moves the weighted sums to p
  // (shiftWeightedValues): they must be the sums about p of the points in the ball, weighted by w (dv: dw/dt), and the
  // omega-values by omega = (4/t^2)(1 - d^2/t^2) (dv: 0), as summed point by point.
  const Points pts = cubeOfPoints(400, gls::Vec3{ 0.0, 0.0, 0.0 }, 0.8, 9);
  const gls::Vec3 p{ 0.05, -0.02, 0.01 };
  const double t = 0.5;
  gls::AggregateMomentsT<Set> aboutO;
  gls::clearMoments(aboutO);
  std::vector<double> w(pts.positions.size()), dw(pts.positions.size()), omega(pts.positions.size());
  for (std::size_t i = 0; i < pts.positions.size(); ++i)
  {
    const double d2 = gls::squaredNorm(pts.positions[i] - p);
    const bool inside = d2 < t * t;
    w[i] = gls::weightAt(d2, t);
    dw[i] = gls::weightDerivativeAt(d2, t);
    omega[i] = inside ? 4.0 / (t * t) * (1.0 - d2 / (t * t)) : 0.0;
    if (inside)
    {
      const gls::Vec3 x = pts.positions[i] - kOrigin;
      double f[Set::kValues];
      Set::pointValues(x, gls::squaredNorm(x), pts.normals[i], f);
      gls::addSampleSums(aboutO, f, d2);
    }
  }
  ASSERT_GT(gls::neighborCount(aboutO), 50.0);
  Values<Set> v{}, dv{};
  gls::weightedValues(aboutO, t, v.data(), dv.data());
  const gls::Vec3 u = kOrigin - p;
  Set::shiftWeightedValues(u, gls::squaredNorm(u), t, v.data(), dv.data());
  const Values<Set> byW = summedValues<Set>(pts, p, [&](std::size_t i) { return w[i]; });
  const Values<Set> byDw = summedValues<Set>(pts, p, [&](std::size_t i) { return dw[i]; });
  const Values<Set> byOmega = summedValues<Set>(pts, p, [&](std::size_t i) { return omega[i]; });
  Values<Set> wantV = byW, wantDv = byDw;
  for (int j = gls::kOffsetOffset; j < gls::kShapeOperatorSquaredPosition; ++j)
  {
    wantV[j] = byOmega[j];
    wantDv[j] = 0.0;
  }
  expectValuesNear(v, wantV, 1e-12, "v");
  expectValuesNear(dv, wantDv, 1e-12, "dv");
}
