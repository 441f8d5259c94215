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

/// v over its length (v not zero).
Vec3 normalized(const Vec3& v)
{
  return (1.0 / std::sqrt(dot(v, v))) * v;
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

/// The per-point values of an estimate in the grid's order, and their scatter to the points' order. The reach is
/// kept only where the caller wants it (empty else); the graph's degrees until the orientation's graph is made,
/// and after only where the caller wants them.
struct PointEstimates
{
  std::vector<Vec3> normals;
  std::vector<int> neighborCounts;
  std::vector<double> spread;
  std::vector<double> reach;
  std::vector<int> graphDegree;
  int graphNeighbors;
  bool graphDegreeWanted;

  PointEstimates(std::size_t count, const NormalEstimationSettings& settings)
    : normals(count, Vec3{ kNaN, kNaN, kNaN })
    , neighborCounts(count, 0)
    , spread(count, kNaN)
    , reach(settings.reachWanted ? count : 0, kNaN)
    , graphDegree(count, settings.graphNeighbors) // the tree's graph grows with the neighbourhood
    , graphNeighbors(settings.graphNeighbors)
    , graphDegreeWanted(settings.graphDegreeWanted)
  {
  }

  /// The graph's degrees are read for the last time (the orientation's graph is made).
  void graphMade()
  {
    if (!graphDegreeWanted)
    {
      std::vector<int>().swap(graphDegree);
    }
  }

  /// Fills the result's arrays (n points; those left out of the grid keep NaN, 0 neighbours and the graph's k).
  void scatter(const std::uint64_t* ids, std::size_t n, NormalEstimationResult& result, int threads) const
  {
    const bool withReach = !reach.empty();
    const bool withDegree = graphDegreeWanted;
    result.normals.assign(3 * n, kNaN);
    result.neighborCounts.assign(n, 0);
    result.spread.assign(n, kNaN);
    result.reach.assign(withReach ? n : 0, kNaN);
    result.graphDegree.assign(withDegree ? n : 0, graphNeighbors);
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
        if (withReach)
        {
          result.reach[id] = reach[s];
        }
        if (withDegree)
        {
          result.graphDegree[id] = graphDegree[s];
        }
      }
    });
  }
};

/// One normal estimation, computed in the grid's order (a point's neighbours and its own values lie near it in
/// memory) and scattered to the points' order once, at the end: the grid, the per-point estimates, and each thread's
/// scratch. Its steps, in order: the first neighbourhoods, the curve test of planar input, the growth of degenerate
/// neighbourhoods, one orientation.
class GridEstimation
{
public:
  GridEstimation(const double* xyz, std::size_t n, const NormalEstimationSettings& settings)
    : Settings(settings)
    , ByRadius(settings.neighborhood == NeighborhoodType::Radius)
    , Planar(commonZ(xyz, n).planar) // 2D input: every finite point in one plane z = const (a curve)
    , Threads(static_cast<std::size_t>(resolveThreadCount(settings.parallel.threads)))
  {
    Grid.setThreads(settings.parallel.threads);
    Grid.build(xyz, nullptr, n,
      ByRadius ? settings.radius : NeighborGrid::suggestCellSizeForKNearest(xyz, n, settings.k));
    const std::size_t count = Grid.view().count;
    Estimates = PointEstimates(count, settings);
    // On planar input, also the in-plane normals and how curve-like each neighbourhood is.
    InPlane.assign(Planar ? count : 0, Vec3{ kNaN, kNaN, kNaN });
    CurveRatio.assign(Planar ? count : 0, kNaN);
    Scratch.resize(Threads);
    Nearest.resize(Threads);
    RunScratch.resize(Threads);
    // The minimum spanning tree's graph links each point to its nearest others: the k-nearest neighbourhoods found
    // first hold them (nearest first), so they are kept for the orientation, which queries only the points they do
    // not answer (32-bit indices: larger grids are queried whole).
    GraphWidth = static_cast<std::size_t>(std::max(settings.graphNeighbors, 1));
    KeepNearest =
      orientsAlongSpanningTree(settings.orientation) && !ByRadius && count < kNoNeighbor;
    NearestOthers.assign(KeepNearest ? count * GraphWidth : 0, kNoNeighbor);
  }

  /// Every point's estimate from its first neighbourhood (k nearest, a cell's points at a time, or the ball).
  bool estimateFirstNeighborhoods(const ParallelOptions& stage)
  {
    const GridView& g = Grid.view();
    return parallelFor(g.count, stage, [&](std::size_t begin, std::size_t end, int t) {
      std::vector<std::uint64_t>& nb = Scratch[static_cast<std::size_t>(t)];
      if (ByRadius)
      {
        for (std::size_t s = begin; s < end; ++s)
        {
          gatherNeighbors(Grid, g.points[s], true, Settings.k, Settings.radius, Nearest[t], nb);
          estimateAt(s, nb);
        }
        return;
      }
      // The k-nearest queries a cell's points at a time (the same answers as one at a time).
      for (std::size_t s = begin; s < end;)
      {
        const std::size_t runEnd = std::min<std::size_t>(end, Grid.cellRunEnd(s));
        Grid.kNearestOfCellRun(s, runEnd, Settings.k, RunScratch[static_cast<std::size_t>(t)],
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
  }

  /// Planar input whose neighbourhoods are mostly lines (median eigenvalue ratio below 0.05) is a 2D curve: its
  /// normals become the in-plane ones. Returns whether it is.
  bool adoptInPlaneNormalsOfACurve()
  {
    std::vector<double> finiteRatios;
    for (double r : CurveRatio)
    {
      if (std::isfinite(r))
      {
        finiteRatios.push_back(r);
      }
    }
    if (finiteRatios.empty())
    {
      return false;
    }
    std::nth_element(finiteRatios.begin(), finiteRatios.begin() + finiteRatios.size() / 2, finiteRatios.end());
    if (!(finiteRatios[finiteRatios.size() / 2] < 0.05))
    {
      return false;
    }
    Estimates.normals = InPlane;
    return true;
  }

  /// Surfaces (not a curve): a neighbourhood whose spread in its tangent plane is below minimumSpread (close to a
  /// line: a scan line, a latitude ring near a pole, three points on a meridian) does not define a normal. It grows
  /// (twice the neighbours, or sqrt(2) times the radius, each step) up to maximumGrowth; where none spans two
  /// dimensions the normal is NaN. Each point's outcome depends on its own neighbourhoods only (deterministic for
  /// any thread count).
  bool growDegenerateNeighborhoods(bool curve, const ParallelOptions& stage)
  {
    const GridView& g = Grid.view();
    std::vector<std::uint64_t> degenerate;
    for (std::size_t s = 0; !curve && s < g.count; ++s)
    {
      if (!finite3(&Estimates.normals[s].x) || !(Estimates.spread[s] >= Settings.minimumSpread))
      {
        degenerate.push_back(s);
      }
    }
    const int steps = adaptiveGrowthSteps(Settings.maximumGrowth);
    return parallelFor(degenerate.size(), stage, [&](std::size_t begin, std::size_t end, int t) {
      for (std::size_t d = begin; d < end; ++d)
      {
        growAt(degenerate[d], steps, Scratch[static_cast<std::size_t>(t)], Nearest[static_cast<std::size_t>(t)]);
      }
    });
  }

  /// The orientations by a rule of each point alone: none, towards or away from a point, up, or agreeing with
  /// reference normals.
  void orientByRule()
  {
    const GridView& g = Grid.view();
    std::vector<Vec3>& normals = Estimates.normals;
    switch (Settings.orientation)
    {
      case NormalOrientation::TowardsPoint:
      case NormalOrientation::AwayFromPoint:
      {
        const double sign = Settings.orientation == NormalOrientation::TowardsPoint ? 1.0 : -1.0;
        for (std::size_t s = 0; s < g.count; ++s)
        {
          const Vec3 toView = Settings.viewpoint - g.points[s];
          flipIfNegative(&normals[s].x, sign * dot(normals[s], toView));
        }
        break;
      }
      case NormalOrientation::Up:
        for (std::size_t s = 0; s < g.count; ++s)
        {
          flipIfNegative(&normals[s].x, dot(normals[s], Settings.up));
        }
        break;
      case NormalOrientation::AgreeWithReference:
        for (std::size_t s = 0; Settings.reference && s < g.count; ++s)
        {
          const double* r = Settings.reference + 3 * g.ids[s];
          if (finite3(r))
          {
            flipIfNegative(&normals[s].x, normals[s].x * r[0] + normals[s].y * r[1] + normals[s].z * r[2]);
          }
        }
        break;
      default: // None; the minimum spanning tree is orientAlongSpanningTree
        break;
    }
  }

  /// The minimum spanning tree's orientation of the points with a normal (n: the input's point count).
  bool orientAlongSpanningTree(std::size_t n, const ParallelOptions& stage, std::size_t& components)
  {
    const GridView& g = Grid.view();
    std::vector<unsigned char> nodes(g.count, 0);
    for (std::size_t s = 0; s < g.count; ++s)
    {
      nodes[s] = finite3(&Estimates.normals[s].x) ? 1 : 0;
    }
    OrientationGraph graph;
    graph.grid = &Grid;
    graph.n = n;
    graph.graphNeighbors = Settings.graphNeighbors;
    graph.sortedDegrees = Estimates.graphDegree.data();
    graph.nodes = nodes.data();
    graph.nearestOthers = std::move(NearestOthers);
    graph.listsMade = [this] { Estimates.graphMade(); };
    graph.rule = Settings.orientation;
    graph.up = normalized(Settings.up);
    return gls::orientAlongSpanningTree(graph, Estimates.normals.data(), stage, components);
  }

  /// The result's arrays in the points' order (n points).
  void scatter(std::size_t n, NormalEstimationResult& result) const
  {
    Estimates.scatter(Grid.view().ids, n, result, Settings.parallel.threads);
  }

private:
  /// One point's estimate from its neighbours (sorted indices, nearest first for k-nearest neighbourhoods).
  void estimateAt(std::size_t s, const std::vector<std::uint64_t>& nb)
  {
    const GridView& g = Grid.view();
    const Vec3 p = g.points[s];
    if (KeepNearest)
    {
      std::size_t j = 0;
      for (std::size_t i = 0; i < nb.size() && j < GraphWidth; ++i)
      {
        if (nb[i] != s)
        {
          NearestOthers[s * GraphWidth + j++] = static_cast<std::uint32_t>(nb[i]);
        }
      }
    }
    Estimates.neighborCounts[s] = static_cast<int>(nb.size());
    if (!Estimates.reach.empty())
    {
      Estimates.reach[s] = farthest(g, p, nb);
    }
    Vec3 normal;
    if (pcaNormal(g, p, nb, normal, Estimates.spread[s]))
    {
      Estimates.normals[s] = normal;
    }
    if (Planar && pcaNormal2D(g, p, nb, normal, CurveRatio[s]))
    {
      InPlane[s] = normal;
    }
  }

  /// Grows point s's neighbourhood until it spans two dimensions or `steps` growth steps are done.
  void growAt(std::size_t s, int steps, std::vector<std::uint64_t>& nb,
    std::vector<std::pair<double, std::uint64_t>>& nearest)
  {
    const GridView& g = Grid.view();
    const Vec3 p = g.points[s];
    Vec3 normal{ kNaN, kNaN, kNaN };
    bool found = false;
    for (int step = 1; step <= steps && !found; ++step)
    {
      Estimates.graphDegree[s] = grownCount(Settings.graphNeighbors, step);
      const int k = grownCount(Settings.k, step);
      gatherNeighbors(Grid, p, ByRadius, k, grownRadius(Settings.radius, step), nearest, nb);
      Estimates.neighborCounts[s] = static_cast<int>(nb.size());
      if (!Estimates.reach.empty())
      {
        Estimates.reach[s] = farthest(g, p, nb);
      }
      found = pcaNormal(g, p, nb, normal, Estimates.spread[s]) && Estimates.spread[s] >= Settings.minimumSpread;
      if (!ByRadius && nb.size() < static_cast<std::size_t>(k))
      {
        break; // every point is already in the neighbourhood
      }
    }
    Estimates.normals[s] = found ? normal : Vec3{ kNaN, kNaN, kNaN };
  }

  const NormalEstimationSettings& Settings;
  const bool ByRadius;
  const bool Planar;
  const std::size_t Threads;
  NeighborGrid Grid;
  PointEstimates Estimates{ 0, NormalEstimationSettings{} };
  std::vector<Vec3> InPlane;
  std::vector<double> CurveRatio;
  std::vector<std::vector<std::uint64_t>> Scratch;
  std::vector<std::vector<std::pair<double, std::uint64_t>>> Nearest;
  std::vector<NeighborGrid::CellRunScratch> RunScratch;
  std::size_t GraphWidth = 1;
  bool KeepNearest = false;
  std::vector<std::uint32_t> NearestOthers;
};

} // namespace

namespace
{
/// The bytes a point of the estimate's result (input order): the normal, the count, the spread, and the reach and
/// the graph's degree where wanted.
double resultBytesPerPoint(const NormalEstimationSettings& settings)
{
  return sizeof(Vec3) + 4.0 + 8.0 + (settings.reachWanted ? 8.0 : 0.0) + (settings.graphDegreeWanted ? 4.0 : 0.0);
}
} // namespace

double normalEstimationBytes(std::size_t n, const NormalEstimationSettings& settings)
{
  // The grid (sorted points and ids, its cell index), the estimates in grid order (what the result holds, and the
  // graph's degree until the graph is made) and, at the end, the result in input order while it is scattered.
  const bool tree = orientsAlongSpanningTree(settings.orientation);
  const double grid = sizeof(Vec3) + 8.0 + 16.0;
  const double kept = resultBytesPerPoint(settings);
  const double degree = settings.graphDegreeWanted ? 0.0 : 4.0;
  // The first neighbourhoods keep each point's nearest others for the tree's graph (32-bit indices).
  const bool keepsNearest = tree && settings.neighborhood == NeighborhoodType::KNearest;
  const double nearest = keepsNearest ? 4.0 * settings.graphNeighbors : 0.0;
  double perPoint = std::max(grid + kept + degree + nearest, grid - 16.0 + 2.0 * kept + degree);
  if (tree)
  {
    // Beside the grid (its cell index released) and the estimates: the graph's lists (32-bit node numbers), their
    // reverse edges (a quarter as many: 13% on the bunny sampled by area) with their offsets, the node flags, and the
    // forest's arrays (tree and sign, whether a node is done, its cheapest edge, each tree's offer).
    const double graph = 4.0 * settings.graphNeighbors + 1.0 * settings.graphNeighbors + 8.0 + 1.0;
    const double forest = 4.0 + 1.0 + 1.0 + 4.0 + 4.0;
    perPoint = std::max(perPoint, grid - 16.0 + kept + graph + forest);
  }
  return perPoint * static_cast<double>(n);
}

double normalEstimationResultBytes(std::size_t n, const NormalEstimationSettings& settings)
{
  return resultBytesPerPoint(settings) * static_cast<double>(n);
}

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
  GridEstimation run(xyz, n, settings);
  if (settings.pointsCopied)
  {
    settings.pointsCopied(); // the grid holds its own copy: xyz is not read again
  }
  // Progress: the first neighbourhoods [0, 0.5], the grown ones [0.5, 0.6], the orientation [0.6, 1] (when it is
  // the minimum spanning tree; else the estimate is the whole range).
  const bool tree = orientsAlongSpanningTree(settings.orientation);
  const double estimateEnd = tree ? 0.6 : 1.0;
  if (!run.estimateFirstNeighborhoods(progressStage(settings.parallel, 0.0, 5.0 / 6.0 * estimateEnd)))
  {
    return false;
  }
  const bool curve = run.adoptInPlaneNormalsOfACurve();
  if (!run.growDegenerateNeighborhoods(curve, progressStage(settings.parallel, 5.0 / 6.0 * estimateEnd, estimateEnd)))
  {
    return false;
  }
  if (tree)
  {
    if (!run.orientAlongSpanningTree(n, progressStage(settings.parallel, 0.6, 1.0), result.components))
    {
      return false;
    }
  }
  else
  {
    run.orientByRule();
  }
  run.scatter(n, result);
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
  const ParallelOptions& parallel, std::size_t& components, const int* degrees, NormalOrientation rule, Vec3 up)
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
  graph.rule = rule;
  graph.up = normalized(up);
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
