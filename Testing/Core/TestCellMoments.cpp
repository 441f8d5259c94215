// The sums a pyramid cell keeps (CellMoments.h): merged from the children they equal the sums of the cell's points;
// and the sample a cell makes for an evaluation point (a linear weight field across the cell, its squared distances
// spread over the scale shells) approximates the weighted sums of its points to a higher order in the cell's size
// than the centroid alone, inside a ball and across a scale's sphere.
#include "TestBinning.h"
#include "TestClouds.h"

#include "gls/CellMoments.h"
#include "gls/MultiresolutionTakeWhole.h"
#include "gls/ScaleSampling.h"
#include "gls/ScaleSpaceEngine.h"
#include "gls/WeightedSums.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace glstest;

namespace
{

/// The nine weighted sums as an array: W, P, N, PN, PP.
std::vector<double> flatten(const gls::WeightedSums& s)
{
  return { s.W, s.P.x, s.P.y, s.P.z, s.N.x, s.N.y, s.N.z, s.PN, s.PP };
}

/// Points of a sphere of radius R centred at the origin, with outward normals, on a lattice of the cube of edge h
/// centred at the sphere's point in direction `dir` (projected onto the sphere).
struct Patch
{
  std::vector<gls::Vec3> points, normals;
};

Patch spherePatch(double R, const gls::Vec3& dir, double h, int m)
{
  Patch patch;
  const double len = std::sqrt(gls::squaredNorm(dir));
  const gls::Vec3 centre = (R / len) * dir;
  for (int i = 0; i < m; ++i)
  {
    for (int j = 0; j < m; ++j)
    {
      for (int k = 0; k < m; ++k)
      {
        const gls::Vec3 q0 = centre + gls::Vec3{ h * ((i + 0.5) / m - 0.5), h * ((j + 0.5) / m - 0.5),
                                       h * ((k + 0.5) / m - 0.5) };
        const double r = std::sqrt(gls::squaredNorm(q0));
        const gls::Vec3 n = (1.0 / r) * q0;
        const gls::Vec3 q = R * n;
        // Keep the projected points that stay in the cube (a patch of the surface crossing it).
        const gls::Vec3 off = q - centre;
        if (std::abs(off.x) <= h / 2 && std::abs(off.y) <= h / 2 && std::abs(off.z) <= h / 2 && k == 0)
        {
          patch.points.push_back(q);
          patch.normals.push_back(n);
        }
      }
    }
  }
  return patch;
}

/// Largest error of `model` against `exact`, each value relative to its natural size (W, W d, W, W d, W d^2).
double relativeError(const std::vector<double>& model, const std::vector<double>& exact, double W, double d)
{
  const double scale[9] = { W, W * d, W * d, W * d, W, W, W, W * d, W * d * d };
  double worst = 0.0;
  for (int j = 0; j < 9; ++j)
  {
    worst = std::max(worst, std::abs(model[j] - exact[j]) / scale[j]);
  }
  return worst;
}

struct PatchErrors
{
  double model = 0.0, centroid = 0.0;               // weighted sums
  double modelDerivative = 0.0, centroidDerivative = 0.0; // their t-derivatives
};

/// The weighted sums at scale t of a patch about p: exactly, as the cell sample (one scale), and with every point
/// at the centroid's distance.
PatchErrors patchErrors(const Patch& patch, const gls::Vec3& p, double t)
{
  gls::WeightedSums s, ds, cs, cds;
  for (std::size_t i = 0; i < patch.points.size(); ++i)
  {
    const gls::Vec3 x = patch.points[i] - p;
    const double d2 = gls::squaredNorm(x);
    gls::accumulate(s, gls::weightAt(d2, t), x, patch.normals[i]);
    gls::accumulate(ds, gls::weightDerivativeAt(d2, t), x, patch.normals[i]);
  }
  gls::PyramidCell cell;
  gls::StoredPoints stored;
  stored.positions = patch.points.data();
  stored.normals = patch.normals.data();
  gls::momentsOfPoints(stored, 0, static_cast<std::uint32_t>(patch.points.size()), patch.points[0], cell);
  const double dc2 = gls::squaredNorm(cell.centroid - p);
  for (std::size_t i = 0; i < patch.points.size(); ++i)
  {
    const gls::Vec3 x = patch.points[i] - p;
    gls::accumulate(cs, gls::weightAt(dc2, t), x, patch.normals[i]);
    gls::accumulate(cds, gls::weightDerivativeAt(dc2, t), x, patch.normals[i]);
  }
  const TestBinning binning({ t });
  gls::AggregateMoments bin;
  gls::clearMoments(bin);
  gls::CellSample sample;
  gls::makeCellSample(cell, p, cell.centroid - p, sample);
  gls::forEachShellOfSpread(binning.View, t * t, dc2 + sample.spreadPerPoint, sample.halfWidth,
    [&](int, const gls::ShellShare& share) { gls::addCellShare(bin, sample, share); }); // one scale: one bin
  gls::WeightedSums ms, mds;
  gls::weightedSumsFromMoments(bin, t, ms, mds);
  const double d = std::sqrt(dc2);
  PatchErrors e;
  e.model = relativeError(flatten(ms), flatten(s), s.W, d);
  e.centroid = relativeError(flatten(cs), flatten(s), s.W, d);
  const double dW = std::abs(ds.W) > 0.0 ? std::abs(ds.W) : 1.0;
  e.modelDerivative = relativeError(flatten(mds), flatten(ds), dW, d);
  e.centroidDerivative = relativeError(flatten(cds), flatten(ds), dW, d);
  return e;
}

} // namespace

TEST(CellMoments, MergedSumsEqualTheSumsOfThePoints)
{
  // Every stored cell of a pyramid (merged level by level from its children) against its points' sums formed
  // directly; and the finer cells' sums are formed from their points (cellMoments).
  const Cloud c = paraboloid(300, 1.0, 0.7, 0.3, 0.01, 0.05, 3);
  const std::vector<double> scales = gls::sampleScales(0.05, 0.5, 10, gls::ScaleSampling::Quadratic);
  gls::ScaleSpaceSettings settings;
  settings.scales = scales;
  settings.evaluation = gls::Evaluation::Multiresolution;
  gls::ScaleSpaceEngine engine(c.points.data(), c.normals.data(), c.size(), settings);
  const gls::MultiresolutionCloud& pyramid = engine.pyramid();
  const gls::MultiresolutionView& v = pyramid.view();
  ASSERT_GT(v.topLevel, gls::kFirstSummedLevel + 1);
  ASSERT_LT(pyramid.cellCount(), pyramid.nodeCount() / 2); // the finest levels keep no sums
  // Levels are stored finest first, each contiguous: the first node of level l - 1 is the first child of the first
  // node of level l.
  std::vector<std::uint64_t> levelStart(static_cast<std::size_t>(v.topLevel) + 2);
  levelStart[v.topLevel] = v.topBegin;
  levelStart[v.topLevel + 1] = v.topEnd;
  for (int l = v.topLevel; l > 0; --l)
  {
    levelStart[l - 1] = v.nodes[levelStart[l]].first;
  }
  ASSERT_EQ(levelStart[0], 0u);
  ASSERT_EQ(levelStart[v.summedLevel], v.summedBegin);
  long checked = 0;
  for (std::uint64_t node = v.summedBegin; node < pyramid.nodeCount(); ++node)
  {
    int level = v.summedLevel;
    while (node >= levelStart[level + 1])
    {
      ++level;
    }
    std::uint32_t first = 0, last = 0;
    gls::pointRange(v.nodes, static_cast<std::uint32_t>(node), level, first, last);
    gls::PyramidCell direct;
    const gls::Vec3 corner = gls::nodeCorner(v.origin, v.nodes[node], v.levelSize[level]);
    gls::momentsOfPoints(v.points, first, last, corner, direct);
    const gls::PyramidCell& stored = v.cells[node - v.summedBegin];
    const double h = v.levelSize[level];
    ASSERT_EQ(stored.count, direct.count);
    const double m = direct.count;
    EXPECT_NEAR(stored.centroid.x, direct.centroid.x, 1e-12);
    EXPECT_NEAR(stored.centroid.y, direct.centroid.y, 1e-12);
    EXPECT_NEAR(stored.centroid.z, direct.centroid.z, 1e-12);
    for (int k = 0; k < 6; ++k)
    {
      ASSERT_NEAR(stored.offsetOffset[k], direct.offsetOffset[k], 1e-10 * m * h * h);
    }
    for (int k = 0; k < 9; ++k)
    {
      ASSERT_NEAR(stored.offsetNormal[k], direct.offsetNormal[k], 1e-10 * m * h);
    }
    const double tol2 = 1e-10 * m * h * h, tol3 = 1e-10 * m * h * h * h;
    ASSERT_NEAR(stored.offsetOffsetDotNormal.x, direct.offsetOffsetDotNormal.x, tol2);
    ASSERT_NEAR(stored.offsetOffsetDotNormal.y, direct.offsetOffsetDotNormal.y, tol2);
    ASSERT_NEAR(stored.offsetOffsetDotNormal.z, direct.offsetOffsetDotNormal.z, tol2);
    ASSERT_NEAR(stored.offsetSquaredOffset.x, direct.offsetSquaredOffset.x, tol3);
    ASSERT_NEAR(stored.offsetSquaredOffset.y, direct.offsetSquaredOffset.y, tol3);
    ASSERT_NEAR(stored.offsetSquaredOffset.z, direct.offsetSquaredOffset.z, tol3);
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

TEST(CellMoments, SampleInsideABallIsThirdOrderInTheCellSize)
{
  // A patch of a sphere of radius 1 in a cube of edge h, 0.3 from p, at scale 0.6 (wholly inside the ball and in
  // one shell): the sample's error falls faster than h^3 when h halves (measured: 14 times), the centroid's only as
  // h^2 (4 times), and the sample is far closer (1,500 times at h = 0.08).
  const gls::Vec3 p = { 0.0, 0.0, 1.0 };
  const gls::Vec3 dir = { 0.3, 0.1, 1.0 };
  const double t = 0.6;
  PatchErrors large = patchErrors(spherePatch(1.0, dir, 0.08, 60), p, t);
  PatchErrors small = patchErrors(spherePatch(1.0, dir, 0.04, 60), p, t);
  EXPECT_LT(small.model, large.model / 10.0);
  EXPECT_GT(small.centroid, large.centroid / 5.0);
  EXPECT_LT(large.model, large.centroid / 100.0);
  EXPECT_LT(small.modelDerivative, large.modelDerivative / 10.0);
  EXPECT_LT(large.modelDerivative, large.centroidDerivative / 100.0);
}

TEST(CellMoments, SampleAcrossAScaleKeepsTheDerivativeWeight)
{
  // The same patch straddling the sphere of radius t: the GLS weight's t-derivative has a kink there, which the
  // centroid turns into an error of the first order in h; the spread of squared distances follows it (measured:
  // 0.024 against 0.62 of the derivative sums, 0.028 against 0.96 of the sums, relative to their size).
  const gls::Vec3 p = { 0.0, 0.0, 1.0 };
  const gls::Vec3 dir = { 0.3, 0.1, 1.0 };
  const Patch patch = spherePatch(1.0, dir, 0.08, 60);
  gls::Vec3 centroid{ 0.0, 0.0, 0.0 };
  for (const gls::Vec3& q : patch.points)
  {
    centroid = centroid + (1.0 / patch.points.size()) * q;
  }
  const double t = std::sqrt(gls::squaredNorm(centroid - p)) * 1.01; // the centroid just inside
  const PatchErrors e = patchErrors(patch, p, t);
  EXPECT_LT(e.modelDerivative, e.centroidDerivative / 10.0);
  EXPECT_LT(e.model, e.centroid / 10.0);
}

TEST(CellMoments, ShareExpansionsAreTheDerivativesOfTheShares)
{
  // The slope and curvature of a share with respect to the spread's mean (what a linearized far cell is moved by)
  // against central differences of pieceShare and pieceShareSlope, for pieces whose ends are ends of the spread or
  // scale spheres, and for a whole spread; and one wrong coefficient would be seen.
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worstSlope = 0.0, worstCurvature = 0.0;
  long pieces = 0;
  for (int trial = 0; trial < 4000; ++trial)
  {
    const double mean = 1.0 + unit(random), half = 0.1 + 0.4 * unit(random);
    double e0 = mean - half + 2.0 * half * unit(random), e1 = mean - half + 2.0 * half * unit(random);
    if (e0 > e1)
    {
      std::swap(e0, e1);
    }
    const bool lowFixed = (trial & 1) != 0, highFixed = (trial & 2) != 0;
    const auto bounds = [&](double m, double& u, double& w) {
      u = lowFixed ? e0 : m - half;
      w = highFixed ? e1 : m + half;
    };
    const double h = 1e-5;
    double u = 0.0, w = 0.0, u1 = 0.0, w1 = 0.0, u2 = 0.0, w2 = 0.0;
    bounds(mean, u, w);
    bounds(mean + h, u1, w1);
    bounds(mean - h, u2, w2);
    if (!(w2 > u2 && w1 > u1 && w > u))
    {
      continue;
    }
    ++pieces;
    const gls::SpreadDensity d = gls::spreadDensity(half);
    const gls::ShellShare slope = gls::pieceShareSlope(mean, d, u, w, lowFixed, highFixed);
    const gls::ShellShare curvature = gls::pieceShareCurvature(mean, d, u, w, lowFixed, highFixed);
    const gls::ShellShare a = gls::pieceShare(mean + h, d, u1, w1), b = gls::pieceShare(mean - h, d, u2, w2);
    const gls::ShellShare sa = gls::pieceShareSlope(mean + h, d, u1, w1, lowFixed, highFixed);
    const gls::ShellShare sb = gls::pieceShareSlope(mean - h, d, u2, w2, lowFixed, highFixed);
    for (int j = 0; j < 3; ++j)
    {
      const double dm = (a.m[j] - b.m[j]) / (2.0 * h), dc = (a.c[j] - b.c[j]) / (2.0 * h);
      const double ddm = (sa.m[j] - sb.m[j]) / (2.0 * h), ddc = (sa.c[j] - sb.c[j]) / (2.0 * h);
      worstSlope = std::max({ worstSlope, std::abs(dm - slope.m[j]) / (1.0 + std::abs(dm)),
        std::abs(dc - slope.c[j]) / (1.0 + std::abs(dc)) });
      worstCurvature = std::max({ worstCurvature, std::abs(ddm - curvature.m[j]) / (1.0 + std::abs(ddm)),
        std::abs(ddc - curvature.c[j]) / (1.0 + std::abs(ddc)) });
    }
  }
  EXPECT_GT(pieces, 2000);
  EXPECT_LT(worstSlope, 1e-6);
  EXPECT_LT(worstCurvature, 1e-6);
  // A whole spread: m = (1, mean, mean^2 + V), c = (0, 2, 4 mean).
  const gls::ShellShareExpansion e = gls::wholeShareExpansion(1.3, 0.2);
  const gls::ShellShare up = gls::wholeShare(1.3 + 1e-6, 0.2), down = gls::wholeShare(1.3 - 1e-6, 0.2);
  for (int j = 0; j < 3; ++j)
  {
    EXPECT_NEAR(e.slope.m[j], (up.m[j] - down.m[j]) / 2e-6, 1e-8);
    EXPECT_NEAR(e.slope.c[j], (up.c[j] - down.c[j]) / 2e-6, 1e-8);
  }
  EXPECT_EQ(e.curvature.m[2], 2.0);
  EXPECT_EQ(e.curvature.c[2], 0.0);
}
