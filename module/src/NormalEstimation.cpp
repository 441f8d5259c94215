#include "gls/NormalEstimation.h"

#include "gls/NeighborGrid.h"
#include "gls/Numeric.h"
#include "gls/Planarity.h"
#include "gls/PointScaleSpace.h"

#include "MinimumSpanningOrientation.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace gls
{
namespace
{

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool finite3(const double* v)
{
  return isFinite(v[0]) && isFinite(v[1]) && isFinite(v[2]);
}

/// 2D input (every point in the plane z = const): the in-plane normal of the neighbours' principal line and the
/// ratio of the small to the large eigenvalue (near 0 on a curve, of order 1 on an area); false when fewer than 3
/// neighbours or all at one place.
bool pcaNormal2D(
  const GridView& g, const Vec3& p, const std::vector<std::uint64_t>& neighbors, Vec3& normal, double& ratio)
{
  if (neighbors.size() < 3)
  {
    return false;
  }
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (std::uint64_t i : neighbors)
  {
    const Vec3 x = g.points[i] - p;
    mean += Eigen::Vector2d(x.x, x.y);
  }
  mean /= static_cast<double>(neighbors.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (std::uint64_t i : neighbors)
  {
    const Vec3 x = g.points[i] - p;
    const Eigen::Vector2d d = Eigen::Vector2d(x.x, x.y) - mean;
    cov += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(cov);
  if (solver.info() != Eigen::Success || !(solver.eigenvalues()(1) > 0.0))
  {
    return false;
  }
  const Eigen::Vector2d v = solver.eigenvectors().col(0).normalized();
  normal = { v(0), v(1), 0.0 };
  ratio = solver.eigenvalues()(0) / solver.eigenvalues()(1);
  return finite3(&normal.x);
}

/// Smallest-eigenvalue eigenvector of the covariance of the neighbours (local coordinates around p) and the spread
/// of the neighbourhood in its tangent plane (middle over largest eigenvalue: 0 on a line, 1 when isotropic); false
/// when fewer than 3 neighbours or when the neighbours are (numerically) on a line or at one place.
bool pcaNormal(
  const GridView& g, const Vec3& p, const std::vector<std::uint64_t>& neighbors, Vec3& normal, double& spread)
{
  spread = kNaN;
  if (neighbors.size() < 3)
  {
    return false;
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::uint64_t i : neighbors)
  {
    const Vec3 x = g.points[i] - p;
    mean += Eigen::Vector3d(x.x, x.y, x.z);
  }
  mean /= static_cast<double>(neighbors.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (std::uint64_t i : neighbors)
  {
    const Vec3 x = g.points[i] - p;
    const Eigen::Vector3d d = Eigen::Vector3d(x.x, x.y, x.z) - mean;
    cov += d * d.transpose();
  }
  // The closed form (Eigen's computeDirect) instead of the QR iterations: 2.3 times faster, and on the bunny and
  // the rocker arm sampled to 1M points (16 nearest) its normals are within 1.5e-6 degree of the iterations'.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(cov);
  if (solver.info() != Eigen::Success)
  {
    return false;
  }
  const Eigen::Vector3d lambda = solver.eigenvalues(); // ascending
  if (!(lambda(2) > 0.0))
  {
    return false;
  }
  spread = std::max(lambda(1), 0.0) / lambda(2);
  if (!(lambda(1) > 1e-12 * lambda(2)))
  {
    return false;
  }
  const Eigen::Vector3d v = solver.eigenvectors().col(0).normalized();
  normal = { v(0), v(1), v(2) };
  return finite3(&normal.x);
}

/// The distance from p to the farthest of its neighbours (0 without any).
double farthest(const GridView& g, const Vec3& p, const std::vector<std::uint64_t>& neighbors)
{
  double d2 = 0.0;
  for (std::uint64_t i : neighbors)
  {
    const Vec3 x = g.points[i] - p;
    d2 = std::max(d2, x.x * x.x + x.y * x.y + x.z * x.z);
  }
  return std::sqrt(d2);
}

/// The neighbours of p: its k nearest points, or every point closer than radius (scratch reused).
void gatherNeighbors(const NeighborGrid& grid, const Vec3& p, bool byRadius, int k, double radius,
  std::vector<std::pair<double, std::uint64_t>>& knn, std::vector<std::uint64_t>& nb)
{
  nb.clear();
  if (byRadius)
  {
    forEachInBall(grid.view(), p, radius, [&](std::uint64_t i, const Vec3&, double) { nb.push_back(i); });
    return;
  }
  grid.kNearest(p, k, knn);
  for (const auto& c : knn)
  {
    nb.push_back(c.second);
  }
}

void flipIfNegative(double* n, double s)
{
  if (s < 0.0)
  {
    n[0] = -n[0];
    n[1] = -n[1];
    n[2] = -n[2];
  }
}

/// Growth steps (each doubles the neighbour count) allowed by maximumGrowth.
int adaptiveGrowthSteps(double maximumGrowth)
{
  int steps = 0;
  while (steps < 30 && std::ldexp(1.0, steps + 1) <= maximumGrowth * (1.0 + 1e-12))
  {
    ++steps;
  }
  return steps;
}

/// A neighbour count (the k of the neighbourhood, or of the tree's graph) after `step` growth steps: doubled each.
int grownCount(int count, int step)
{
  return static_cast<int>(std::min(std::ldexp(static_cast<double>(count), step), 1e9));
}

/// The radius after `step` growth steps: sqrt(2) times per step (twice the neighbours on a surface).
double grownRadius(double radius, int step)
{
  return radius * std::sqrt(std::ldexp(1.0, step));
}

/// The per-point values of an estimate in the grid's order, and their scatter to the points' order.
struct PointEstimates
{
  std::vector<Vec3> normals;
  std::vector<int> neighborCounts;
  std::vector<double> spread;
  std::vector<double> reach;
  std::vector<int> graphDegree;
  int graphNeighbors;

  PointEstimates(std::size_t count, int graphNeighbors)
    : normals(count, Vec3{ kNaN, kNaN, kNaN })
    , neighborCounts(count, 0)
    , spread(count, kNaN)
    , reach(count, kNaN)
    , graphDegree(count, graphNeighbors) // the tree's graph grows with the neighbourhood
    , graphNeighbors(graphNeighbors)
  {
  }

  /// Fills the result's arrays (n points; those left out of the grid keep NaN, 0 neighbours and the graph's k).
  void scatter(const std::uint64_t* ids, std::size_t n, NormalEstimationResult& result, int threads) const
  {
    result.normals.assign(3 * n, kNaN);
    result.neighborCounts.assign(n, 0);
    result.spread.assign(n, kNaN);
    result.reach.assign(n, kNaN);
    result.graphDegree.assign(n, graphNeighbors);
    ParallelOptions options;
    options.threads = threads;
    options.chunk = 65536;
    parallelFor(normals.size(), options, [&](std::size_t begin, std::size_t end, int) {
      for (std::size_t s = begin; s < end; ++s)
      {
        const std::uint64_t id = ids[s];
        result.normals[3 * id] = normals[s].x;
        result.normals[3 * id + 1] = normals[s].y;
        result.normals[3 * id + 2] = normals[s].z;
        result.neighborCounts[id] = neighborCounts[s];
        result.spread[id] = spread[s];
        result.reach[id] = reach[s];
        result.graphDegree[id] = graphDegree[s];
      }
    });
  }
};

} // namespace

double reachableRadius(const NormalEstimationSettings& settings)
{
  return grownRadius(settings.radius, adaptiveGrowthSteps(settings.maximumGrowth));
}

int reachableNeighbors(const NormalEstimationSettings& settings)
{
  return grownCount(settings.k, adaptiveGrowthSteps(settings.maximumGrowth));
}

bool estimateNormals(
  const double* xyz, std::size_t n, const NormalEstimationSettings& settings, NormalEstimationResult& result)
{
  result.components = 0;
  const bool byRadius = settings.neighborhood == NeighborhoodType::Radius;
  // 2D input: every finite point in one plane z = const (a curve); its normals are in that plane.
  const bool planar = commonZ(xyz, n).planar;
  const double cellSize =
    byRadius ? settings.radius : NeighborGrid::suggestCellSizeForKNearest(xyz, n, settings.k);
  NeighborGrid grid;
  grid.setThreads(settings.parallel.threads);
  grid.build(xyz, nullptr, n, cellSize);
  const GridView& g = grid.view();

  // Every per-point value is computed in the grid's order (a point's neighbours and its own values lie near it in
  // memory) and scattered to the points' order once, at the end.
  PointEstimates est(g.count, settings.graphNeighbors);
  // On planar input, also the in-plane normals and how curve-like each neighbourhood is.
  std::vector<Vec3> inPlane(planar ? g.count : 0, Vec3{ kNaN, kNaN, kNaN });
  std::vector<double> curveRatio(planar ? g.count : 0, kNaN);

  const int threads = resolveThreadCount(settings.parallel.threads);
  std::vector<std::vector<std::uint64_t>> scratch(static_cast<std::size_t>(threads));
  std::vector<std::vector<std::pair<double, std::uint64_t>>> knn(static_cast<std::size_t>(threads));
  // The minimum spanning tree's graph links each point to its nearest others: the k-nearest neighbourhoods found
  // here hold them (nearest first), so they are kept for the orientation, which queries only the points they do not
  // answer (32-bit indices: larger grids are queried whole).
  const bool tree = settings.orientation == NormalOrientation::MinimumSpanningTree;
  const std::size_t graphWidth = static_cast<std::size_t>(std::max(settings.graphNeighbors, 1));
  const bool keepNearest = tree && !byRadius && g.count < kNoNeighbor;
  std::vector<std::uint32_t> nearestOthers(keepNearest ? g.count * graphWidth : 0, kNoNeighbor);

  // Progress: the first neighbourhoods [0, 0.5], the grown ones [0.5, 0.6], the orientation [0.6, 1] (when it is
  // the minimum spanning tree; else the estimate is the whole range).
  const double estimateEnd = tree ? 0.6 : 1.0;
  const ParallelOptions firstStage = progressStage(settings.parallel, 0.0, 5.0 / 6.0 * estimateEnd);
  // One point's estimate from its neighbours (sorted indices, nearest first for k-nearest neighbourhoods).
  const auto estimateAt = [&](std::size_t s, const std::vector<std::uint64_t>& nb) {
    const Vec3 p = g.points[s];
    if (keepNearest)
    {
      std::size_t j = 0;
      for (std::size_t i = 0; i < nb.size() && j < graphWidth; ++i)
      {
        if (nb[i] != s)
        {
          nearestOthers[s * graphWidth + j++] = static_cast<std::uint32_t>(nb[i]);
        }
      }
    }
    est.neighborCounts[s] = static_cast<int>(nb.size());
    est.reach[s] = farthest(g, p, nb);
    Vec3 normal;
    if (pcaNormal(g, p, nb, normal, est.spread[s]))
    {
      est.normals[s] = normal;
    }
    if (planar && pcaNormal2D(g, p, nb, normal, curveRatio[s]))
    {
      inPlane[s] = normal;
    }
  };
  std::vector<NeighborGrid::CellRunScratch> runScratch(static_cast<std::size_t>(threads));
  const bool completed =
    parallelFor(g.count, firstStage, [&](std::size_t begin, std::size_t end, int t) {
      std::vector<std::uint64_t>& nb = scratch[t];
      if (byRadius)
      {
        for (std::size_t s = begin; s < end; ++s)
        {
          gatherNeighbors(grid, g.points[s], true, settings.k, settings.radius, knn[t], nb);
          estimateAt(s, nb);
        }
        return;
      }
      // The k-nearest queries a cell's points at a time (the same answers as one at a time).
      for (std::size_t s = begin; s < end;)
      {
        const std::size_t runEnd = std::min<std::size_t>(end, grid.cellRunEnd(s));
        grid.kNearestOfCellRun(s, runEnd, settings.k, runScratch[static_cast<std::size_t>(t)],
          [&](std::uint64_t q, const std::vector<std::pair<double, std::uint64_t>>& nearest) {
            nb.clear();
            for (const auto& c : nearest)
            {
              nb.push_back(c.second);
            }
            estimateAt(q, nb);
          });
        s = runEnd;
      }
    });
  if (!completed)
  {
    return false;
  }
  // Planar input whose neighbourhoods are mostly lines (median eigenvalue ratio below 0.05) is a 2D curve: its
  // normals lie in the plane.
  bool curve = false;
  if (planar)
  {
    std::vector<double> finiteRatios;
    for (double r : curveRatio)
    {
      if (std::isfinite(r))
      {
        finiteRatios.push_back(r);
      }
    }
    if (!finiteRatios.empty())
    {
      std::nth_element(finiteRatios.begin(), finiteRatios.begin() + finiteRatios.size() / 2, finiteRatios.end());
      if (finiteRatios[finiteRatios.size() / 2] < 0.05)
      {
        est.normals = inPlane;
        curve = true;
      }
    }
  }

  // Surfaces: a neighbourhood whose spread in its tangent plane is below minimumSpread (close to a line: a scan
  // line, a latitude ring near a pole, three points on a meridian) does not define a normal. It grows (twice the
  // neighbours, or sqrt(2) times the radius, each step) up to maximumGrowth; where none spans two dimensions the
  // normal is NaN. Each point's outcome depends on its own neighbourhoods only (deterministic for any thread count).
  std::vector<std::uint64_t> degenerate;
  for (std::size_t s = 0; !curve && s < g.count; ++s)
  {
    if (!finite3(&est.normals[s].x) || !(est.spread[s] >= settings.minimumSpread))
    {
      degenerate.push_back(s);
    }
  }
  const int steps = adaptiveGrowthSteps(settings.maximumGrowth);
  const ParallelOptions growthStage = progressStage(settings.parallel, 5.0 / 6.0 * estimateEnd, estimateEnd);
  const bool grown = parallelFor(degenerate.size(), growthStage, [&](std::size_t begin, std::size_t end, int t) {
      std::vector<std::uint64_t>& nb = scratch[t];
      for (std::size_t d = begin; d < end; ++d)
      {
        const std::size_t s = degenerate[d];
        const Vec3 p = g.points[s];
        Vec3 normal{ kNaN, kNaN, kNaN };
        bool found = false;
        for (int step = 1; step <= steps && !found; ++step)
        {
          est.graphDegree[s] = grownCount(settings.graphNeighbors, step);
          const int k = grownCount(settings.k, step);
          gatherNeighbors(grid, p, byRadius, k, grownRadius(settings.radius, step), knn[t], nb);
          est.neighborCounts[s] = static_cast<int>(nb.size());
          est.reach[s] = farthest(g, p, nb);
          found = pcaNormal(g, p, nb, normal, est.spread[s]) && est.spread[s] >= settings.minimumSpread;
          if (!byRadius && nb.size() < static_cast<std::size_t>(k))
          {
            break; // every point is already in the neighbourhood
          }
        }
        est.normals[s] = found ? normal : Vec3{ kNaN, kNaN, kNaN };
      }
    });
  if (!grown)
  {
    return false;
  }

  switch (settings.orientation)
  {
    case NormalOrientation::None:
      break;
    case NormalOrientation::TowardsPoint:
    case NormalOrientation::AwayFromPoint:
    {
      const double sign = settings.orientation == NormalOrientation::TowardsPoint ? 1.0 : -1.0;
      for (std::size_t s = 0; s < g.count; ++s)
      {
        const Vec3 toView = settings.viewpoint - g.points[s];
        flipIfNegative(&est.normals[s].x, sign * dot(est.normals[s], toView));
      }
      break;
    }
    case NormalOrientation::Up:
      for (std::size_t s = 0; s < g.count; ++s)
      {
        flipIfNegative(&est.normals[s].x, dot(est.normals[s], settings.up));
      }
      break;
    case NormalOrientation::AgreeWithReference:
      for (std::size_t s = 0; settings.reference && s < g.count; ++s)
      {
        const double* r = settings.reference + 3 * g.ids[s];
        if (finite3(r))
        {
          flipIfNegative(&est.normals[s].x, est.normals[s].x * r[0] + est.normals[s].y * r[1] + est.normals[s].z * r[2]);
        }
      }
      break;
    case NormalOrientation::MinimumSpanningTree:
    {
      // The graph's nodes: the grid's points with a normal.
      std::vector<unsigned char> nodes(g.count, 0);
      for (std::size_t s = 0; s < g.count; ++s)
      {
        nodes[s] = finite3(&est.normals[s].x) ? 1 : 0;
      }
      OrientationGraph graph;
      graph.grid = &grid;
      graph.n = n;
      graph.graphNeighbors = settings.graphNeighbors;
      graph.sortedDegrees = est.graphDegree.data();
      graph.nodes = nodes.data();
      graph.nearestOthers = std::move(nearestOthers);
      if (!orientAlongSpanningTree(
            graph, est.normals.data(), progressStage(settings.parallel, 0.6, 1.0), result.components))
      {
        return false;
      }
      break;
    }
  }
  est.scatter(g.ids, n, result, settings.parallel.threads);
  return true;
}

bool refineNormalsByGls(const double* xyz, std::size_t n, const std::vector<double>& reach, double factor,
  double* normals, const ParallelOptions& parallel)
{
  std::vector<double> scales;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (std::isfinite(reach[i]) && reach[i] > 0.0)
    {
      scales.push_back(factor * reach[i]);
    }
  }
  if (scales.empty())
  {
    return true;
  }
  std::nth_element(scales.begin(), scales.begin() + scales.size() / 2, scales.end());
  std::vector<double> unit;
  std::vector<unsigned char> admit;
  normalizeAndAdmit(xyz, normals, n, unit, admit);
  NeighborGrid grid;
  grid.setThreads(parallel.threads);
  grid.build(xyz, unit.data(), n, scales[scales.size() / 2], admit.data());
  const GridView& g = grid.view();
  std::vector<double> out(normals, normals + 3 * n);
  const bool completed = parallelFor(n, parallel, [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t i = begin; i < end; ++i)
    {
      const double t = factor * reach[i];
      if (!admit[i] || !(t > 0.0) || !std::isfinite(t))
      {
        continue;
      }
      const ScaleSample s = evaluateOneScale(g, { xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] }, t, 4.0);
      if (s.valid && finite3(&s.eta.x))
      {
        out[3 * i] = s.eta.x;
        out[3 * i + 1] = s.eta.y;
        out[3 * i + 2] = s.eta.z;
      }
    }
  });
  if (!completed)
  {
    return false;
  }
  std::copy(out.begin(), out.end(), normals);
  return true;
}

double medianKNearestDistance(const double* xyz, std::size_t n, int k, std::size_t samples)
{
  std::size_t finite = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    finite += finite3(xyz + 3 * i) ? 1 : 0;
  }
  if (finite < 2 || samples == 0)
  {
    return 0.0;
  }
  NeighborGrid grid;
  grid.build(xyz, nullptr, n, NeighborGrid::suggestCellSizeForKNearest(xyz, n, k));
  const std::size_t stride = std::max<std::size_t>(1, (n + samples - 1) / samples);
  std::vector<std::pair<double, std::uint64_t>> knn;
  std::vector<double> distances;
  for (std::size_t i = 0; i < n; i += stride)
  {
    const double* p = xyz + 3 * i;
    if (finite3(p))
    {
      grid.kNearest({ p[0], p[1], p[2] }, k, knn);
      distances.push_back(std::sqrt(knn.back().first));
    }
  }
  if (distances.empty())
  {
    return 0.0;
  }
  std::nth_element(distances.begin(), distances.begin() + distances.size() / 2, distances.end());
  return distances[distances.size() / 2];
}

double kNearestReach(const double* xyz, std::size_t n, int k, const ParallelOptions& parallel)
{
  std::size_t finite = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    finite += finite3(xyz + 3 * i) ? 1 : 0;
  }
  if (finite == 0)
  {
    return 0.0;
  }
  if (finite < static_cast<std::size_t>(k))
  {
    return std::numeric_limits<double>::infinity();
  }
  NeighborGrid grid;
  grid.setThreads(parallel.threads);
  grid.build(xyz, nullptr, n, NeighborGrid::suggestCellSizeForKNearest(xyz, n, k));
  const GridView& g = grid.view();
  const int threads = resolveThreadCount(parallel.threads);
  std::vector<double> reach(static_cast<std::size_t>(threads), 0.0);
  std::vector<std::vector<std::pair<double, std::uint64_t>>> knn(static_cast<std::size_t>(threads));
  ParallelOptions options;
  options.threads = parallel.threads;
  parallelFor(g.count, options, [&](std::size_t begin, std::size_t end, int t) {
    for (std::size_t s = begin; s < end; ++s)
    {
      grid.kNearest(g.points[s], k, knn[t]);
      if (!knn[t].empty())
      {
        reach[t] = std::max(reach[t], knn[t].back().first);
      }
    }
  });
  return std::sqrt(*std::max_element(reach.begin(), reach.end()));
}

bool orientByMinimumSpanningTree(const double* xyz, std::size_t n, int graphNeighbors, double* normals,
  const ParallelOptions& parallel, std::size_t& components, const int* degrees)
{
  // Graph nodes: points with a finite position and a finite normal.
  std::vector<unsigned char> usable(n, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    usable[i] = finite3(xyz + 3 * i) && finite3(normals + 3 * i);
  }
  NeighborGrid grid;
  grid.setThreads(parallel.threads);
  grid.build(xyz, normals, n, NeighborGrid::suggestCellSizeForKNearest(xyz, n, graphNeighbors + 1), usable.data());
  std::vector<unsigned char>().swap(usable);
  const GridView& g = grid.view();
  std::vector<Vec3> sortedNormals(g.normals, g.normals + g.count);
  std::vector<int> sortedDegrees(degrees ? g.count : 0);
  for (std::size_t s = 0; s < sortedDegrees.size(); ++s)
  {
    sortedDegrees[s] = degrees[g.ids[s]];
  }
  OrientationGraph graph;
  graph.grid = &grid;
  graph.n = n;
  graph.graphNeighbors = graphNeighbors;
  graph.sortedDegrees = degrees ? sortedDegrees.data() : nullptr;
  if (!orientAlongSpanningTree(graph, sortedNormals.data(), parallel, components))
  {
    return false;
  }
  for (std::size_t s = 0; s < g.count; ++s)
  {
    double* ni = normals + 3 * g.ids[s];
    ni[0] = sortedNormals[s].x;
    ni[1] = sortedNormals[s].y;
    ni[2] = sortedNormals[s].z;
  }
  return true;
}

} // namespace gls
