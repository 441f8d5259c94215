// The principal curvatures' accuracy table (docs/performance.md, "Principal curvatures"): per analytic shape and place
// (AnalyticSurfaces.h, scanner-like sampling), normals (exact, or estimated from the sampled positions as GLS Normal
// Estimation does: PCA of the 16 nearest points, its default, or of 64; oriented here by the exact normal), sampling
// density (points in the smallest ball) and noise (0 and 0.1% of the sampled patch's diagonal, along the normals),
// at t = 3, 4 and 5% of the smallest radius of curvature: p99 of |k - k_true| / max|k_true| and p99 of the angle of
// d1 to the true one where |k1 - k2| >= 0.2 max|k|. With CGAL's jet fitting (Monge form of degree 2 over the points within t, oriented by the
// exact normal) at the same points and scales when CMake found CGAL: the peer column.
//
//   glsCurvatureBenchmark [--quick]      (--quick: one density, two shapes: the CI smoke run)
#include "AnalyticSurfaces.h"

#include "gls/NeighborGrid.h"
#include "gls/NormalEstimation.h"
#include "gls/PointScaleSpace.h"
#include "gls/ScaleSampling.h"
#include "gls/ShapeOperator.h"

#ifdef GLS_BENCHMARK_WITH_CGAL
#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/Simple_cartesian.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

using namespace glstest;

namespace
{

struct Site
{
  Surface surface;
  double u, v, du, dv;   ///< the place and the parameter box sampled around it
  double smallestRadius; ///< of curvature over the evaluated points (length)
};

#ifdef GLS_BENCHMARK_WITH_CGAL
/// CGAL's degree-2 jet (Monge form) over the points within t of p, its normal towards n; in this project's sign
/// convention (positive on a sphere with outward normals: CGAL's Monge coefficients have the opposite sign).
gls::PrincipalCurvatures cgalJet(const gls::GridView& g, const gls::Vec3& p, double t, const gls::Vec3& n)
{
  using Kernel = CGAL::Simple_cartesian<double>;
  using Fitting = CGAL::Monge_via_jet_fitting<Kernel>;
  std::vector<Kernel::Point_3> points;
  gls::forEachInBall(g, p, t, [&](std::uint64_t, const gls::Vec3& x, double) {
    points.emplace_back(p.x + x.x, p.y + x.y, p.z + x.z);
  });
  if (points.size() < 6)
  {
    return gls::undefinedCurvatures();
  }
  Fitting fitting;
  Fitting::Monge_form m = fitting(points.begin(), points.end(), 2, 2);
  m.comply_wrt_given_normal(Kernel::Vector_3(n.x, n.y, n.z));
  const Kernel::Vector_3 dmin = m.minimal_principal_direction(), dmax = m.maximal_principal_direction();
  gls::PrincipalCurvatures c;
  c.k1 = -m.principal_curvatures(1);
  c.k2 = -m.principal_curvatures(0);
  c.d1 = { dmin.x(), dmin.y(), dmin.z() };
  c.d2 = { dmax.x(), dmax.y(), dmax.z() };
  return c;
}
#endif

/// Where the normals GLS reads come from.
enum class Normals
{
  Exact,   ///< the surface's
  Pca16,   ///< GLS Normal Estimation's defaults: PCA of the 16 nearest points, no refinement
  Pca64    ///< its NumberOfNeighbors 64: a larger neighbourhood, for noisy scans
};

const char* nameOf(Normals n)
{
  return n == Normals::Exact ? "exact" : n == Normals::Pca16 ? "PCA 16" : "PCA 64";
}

/// The normals estimated from the cloud's points as GLS Normal Estimation does (`how`), oriented by the exact ones;
/// NaN where undefined.
std::vector<double> estimatedNormals(const Cloud& cloud, Normals how)
{
  gls::NormalEstimationSettings settings;
  settings.orientation = gls::NormalOrientation::AgreeWithReference;
  settings.reference = cloud.normals.data();
  settings.k = how == Normals::Pca64 ? 64 : 16;
  settings.reachWanted = false;
  settings.graphDegreeWanted = false;
  gls::NormalEstimationResult result;
  gls::estimateNormals(cloud.points.data(), cloud.size(), settings, result);
  return result.normals;
}

/// One row: GLS (and CGAL) at the points of the patch within the largest scale of the site.
void row(const Site& site, double pointsInSmallestBall, double noiseFraction, Normals normals, unsigned seed)
{
  const std::vector<double> scales{ 0.03 * site.smallestRadius, 0.04 * site.smallestRadius,
    0.05 * site.smallestRadius };
  const double t = scales.back();
  const double density = pointsInSmallestBall / (3.14159265358979 * scales[0] * scales[0]);
  // The noise: a fraction of the noise-free patch's diagonal.
  const Patch clean = samplePatch(site.surface, site.u, site.v, site.du, site.dv, density, seed);
  const double diagonal = boxDiagonal(clean.cloud.points);
  Patch patch = noiseFraction > 0.0
    ? samplePatch(site.surface, site.u, site.v, site.du, site.dv, density, seed, noiseFraction * diagonal)
    : clean;
  const std::vector<double> exactNormals = patch.cloud.normals; // the jets' orientation (they read no normals)
  if (normals != Normals::Exact)
  {
    patch.cloud.normals = estimatedNormals(patch.cloud, normals);
  }
  gls::NeighborGrid grid;
  grid.build(patch.cloud.points.data(), patch.cloud.normals.data(), patch.cloud.size(), t / 4.0);
  std::vector<double> squared;
  for (double s : scales)
  {
    squared.push_back(s * s);
  }
  const gls::BinningTable table = gls::makeBinningTable(squared);
  gls::ScaleBinning b;
  b.scales = scales.data();
  b.squaredScales = squared.data();
  b.count = 3;
  b.table = table.cells.data();
  b.tableSize = static_cast<int>(table.cells.size());
  b.inverseCellWidth = table.inverseCellWidth;
  std::vector<gls::MomentsT<gls::ShapeOperatorMoments>> bins(3);
  std::vector<gls::CurvatureSample> out(3);
  CurvatureErrors gls, peer;
  const gls::Vec3 centre = site.surface.X(site.u, site.v);
  for (std::size_t i = 0; i < patch.cloud.size(); i += 7)
  {
    const gls::Vec3 p{ patch.cloud.points[3 * i], patch.cloud.points[3 * i + 1], patch.cloud.points[3 * i + 2] };
    if (gls::squaredNorm(p - centre) > t * t)
    {
      continue;
    }
    const gls::PrincipalCurvatures want = truth(site.surface, patch.u[i], patch.v[i]);
    gls::evaluateAllScales<gls::ShapeOperatorMoments>(grid.view(), p, b, 6.0, bins.data(), out.data());
    for (int k = 0; k < 3; ++k)
    {
      gls.add(out[k].principal, want);
#ifdef GLS_BENCHMARK_WITH_CGAL
      const gls::Vec3 n{ exactNormals[3 * i], exactNormals[3 * i + 1], exactNormals[3 * i + 2] };
      peer.add(cgalJet(grid.view(), p, scales[k], n), want);
#endif
    }
  }
  std::printf("| %-9s (%4.2f, %4.2f) | %-7s | %5.0f | %5.2f%% | %7.3f%% | %8.3f | %7.3f%% | %8.3f | %6zu |\n",
    site.surface.name.c_str(), site.u, site.v, nameOf(normals), pointsInSmallestBall, 100.0 * noiseFraction,
    100.0 * percentile99(gls.curvature), percentile99(gls.direction),
    peer.curvature.empty() ? std::nan("") : 100.0 * percentile99(peer.curvature),
    peer.direction.empty() ? std::nan("") : percentile99(peer.direction), gls.curvature.size());
  std::fflush(stdout);
}

} // namespace

int main(int argc, char* argv[])
{
  const bool quick = argc > 1 && !std::strcmp(argv[1], "--quick");
  const double pi = 3.14159265358979;
  std::vector<Site> sites{ { cylinder(0.5), 0.0, 0.0, 0.12, 0.06, 0.5 }, { saddle(), 0.0, 0.0, 0.1, 0.1, 1.0 } };
  if (!quick)
  {
    sites.insert(sites.begin(), { sphere(1.0), 0.3, 0.4, 0.12, 0.12, 1.0 });
    for (const Site& s : std::vector<Site>{ { torus(1.0, 0.4), 0.0, 0.0, 0.05, 0.12, 0.4 },
           { torus(1.0, 0.4), 0.5, 0.5 * pi, 0.05, 0.12, 0.4 }, { torus(1.0, 0.4), 1.0, pi, 0.08, 0.12, 0.4 },
           { ellipsoid(1.0, 0.7, 0.5), 0.0, 0.0, 0.06, 0.12, 0.25 },
           { ellipsoid(1.0, 0.7, 0.5), 0.9, 0.5, 0.06, 0.06, 0.25 } })
    {
      sites.push_back(s);
    }
  }
#ifdef GLS_BENCHMARK_WITH_CGAL
  std::printf("peer: CGAL %s Monge_via_jet_fitting, degree 2, the points within t\n", CGAL_VERSION_STR);
#else
  std::printf("peer: CGAL not found at build time (its columns are NaN)\n");
#endif
  std::printf("| %-22s | %-7s | %5s | %6s | %8s | %8s | %8s | %8s | %6s |\n", "shape (u, v)", "normals", "pts",
    "noise", "GLS k", "GLS dir", "jet k", "jet dir", "values");
  std::printf("| p99 of |k - k_true| / max|k_true| and of the direction error (degrees) at t = 3, 4, 5%% of the "
              "smallest radius |\n");
  unsigned seed = 1;
  for (const Site& s : sites)
  {
    for (double points : quick ? std::vector<double>{ 250.0 } : std::vector<double>{ 250.0, 1000.0 })
    {
      for (double noise : { 0.0, 0.001 })
      {
        for (Normals normals : { Normals::Exact, Normals::Pca16, Normals::Pca64 })
        {
          row(s, points, noise, normals, seed);
        }
        ++seed;
      }
    }
  }
  std::printf("curvature benchmark complete\n");
  return 0;
}
