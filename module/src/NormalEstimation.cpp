#include "gls/NormalEstimation.h"

#include "gls/NeighborGrid.h"
#include "gls/Numeric.h"
#include "gls/Planarity.h"
#include "gls/PointScaleSpace.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <tuple>

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
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
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

/// The options of one stage of a run: the same threads, progress mapped to [begin, end] of the caller's.
ParallelOptions progressStage(const ParallelOptions& parallel, double begin, double end)
{
  ParallelOptions o = parallel;
  if (parallel.progress)
  {
    o.progress = [&parallel, begin, end](double f) { return parallel.progress(begin + f * (end - begin)); };
  }
  return o;
}

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
  result.normals.assign(3 * n, kNaN);
  result.neighborCounts.assign(n, 0);
  result.spread.assign(n, kNaN);
  result.reach.assign(n, kNaN);
  result.graphDegree.assign(n, settings.graphNeighbors); // the tree's graph grows with the neighbourhood
  result.components = 0;

  const bool byRadius = settings.neighborhood == NeighborhoodType::Radius;
  // 2D input: every finite point in one plane z = const (a curve); its normals are in that plane.
  const bool planar = commonZ(xyz, n).planar;
  const double cellSize =
    byRadius ? settings.radius : NeighborGrid::suggestCellSizeForKNearest(xyz, n, settings.k);
  NeighborGrid grid;
  grid.build(xyz, nullptr, n, cellSize);
  const GridView& g = grid.view();

  // On planar input, also the in-plane normals and how curve-like each neighbourhood is.
  std::vector<double> inPlane(planar ? 3 * n : 0, kNaN), curveRatio(planar ? n : 0, kNaN);

  const int threads = resolveThreadCount(settings.parallel.threads);
  std::vector<std::vector<std::uint64_t>> scratch(static_cast<std::size_t>(threads));
  std::vector<std::vector<std::pair<double, std::uint64_t>>> knn(static_cast<std::size_t>(threads));

  // Progress: the first neighbourhoods [0, 0.5], the grown ones [0.5, 0.6], the orientation [0.6, 1] (when it is
  // the minimum spanning tree; else the estimate is the whole range).
  const double estimateEnd = settings.orientation == NormalOrientation::MinimumSpanningTree ? 0.6 : 1.0;
  const ParallelOptions firstStage = progressStage(settings.parallel, 0.0, 5.0 / 6.0 * estimateEnd);
  const bool completed =
    parallelFor(g.count, firstStage, [&](std::size_t begin, std::size_t end, int t) {
      std::vector<std::uint64_t>& nb = scratch[t];
      for (std::size_t s = begin; s < end; ++s)
      {
        const Vec3 p = g.points[s];
        gatherNeighbors(grid, p, byRadius, settings.k, settings.radius, knn[t], nb);
        const std::uint64_t id = g.ids[s];
        result.neighborCounts[id] = static_cast<int>(nb.size());
        result.reach[id] = farthest(g, p, nb);
        Vec3 normal;
        if (pcaNormal(g, p, nb, normal, result.spread[id]))
        {
          result.normals[3 * id] = normal.x;
          result.normals[3 * id + 1] = normal.y;
          result.normals[3 * id + 2] = normal.z;
        }
        if (planar && pcaNormal2D(g, p, nb, normal, curveRatio[id]))
        {
          inPlane[3 * id] = normal.x;
          inPlane[3 * id + 1] = normal.y;
          inPlane[3 * id + 2] = normal.z;
        }
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
        result.normals = inPlane;
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
    const std::uint64_t id = g.ids[s];
    if (!finite3(&result.normals[3 * id]) || !(result.spread[id] >= settings.minimumSpread))
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
        const std::uint64_t id = g.ids[s];
        Vec3 normal{ kNaN, kNaN, kNaN };
        bool found = false;
        for (int step = 1; step <= steps && !found; ++step)
        {
          result.graphDegree[id] = grownCount(settings.graphNeighbors, step);
          const int k = grownCount(settings.k, step);
          gatherNeighbors(grid, p, byRadius, k, grownRadius(settings.radius, step), knn[t], nb);
          result.neighborCounts[id] = static_cast<int>(nb.size());
          result.reach[id] = farthest(g, p, nb);
          found = pcaNormal(g, p, nb, normal, result.spread[id]) && result.spread[id] >= settings.minimumSpread;
          if (!byRadius && nb.size() < static_cast<std::size_t>(k))
          {
            break; // every point is already in the neighbourhood
          }
        }
        result.normals[3 * id] = found ? normal.x : kNaN;
        result.normals[3 * id + 1] = found ? normal.y : kNaN;
        result.normals[3 * id + 2] = found ? normal.z : kNaN;
      }
    });
  if (!grown)
  {
    return false;
  }

  grid = NeighborGrid(); // the estimate's grid is not needed by the orientation, which builds its own
  double* normals = result.normals.data();
  switch (settings.orientation)
  {
    case NormalOrientation::None:
      break;
    case NormalOrientation::TowardsPoint:
    case NormalOrientation::AwayFromPoint:
    {
      const double sign = settings.orientation == NormalOrientation::TowardsPoint ? 1.0 : -1.0;
      for (std::size_t i = 0; i < n; ++i)
      {
        const double* p = xyz + 3 * i;
        const double toView[3] = { settings.viewpoint.x - p[0], settings.viewpoint.y - p[1],
          settings.viewpoint.z - p[2] };
        double* ni = normals + 3 * i;
        flipIfNegative(ni, sign * (ni[0] * toView[0] + ni[1] * toView[1] + ni[2] * toView[2]));
      }
      break;
    }
    case NormalOrientation::AgreeWithReference:
      for (std::size_t i = 0; settings.reference && i < n; ++i)
      {
        const double* r = settings.reference + 3 * i;
        double* ni = normals + 3 * i;
        if (finite3(r))
        {
          flipIfNegative(ni, ni[0] * r[0] + ni[1] * r[1] + ni[2] * r[2]);
        }
      }
      break;
    case NormalOrientation::MinimumSpanningTree:
    {
      if (!orientByMinimumSpanningTree(xyz, n, settings.graphNeighbors, normals,
            progressStage(settings.parallel, 0.6, 1.0), result.components, result.graphDegree.data()))
      {
        return false;
      }
      break;
    }
  }
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

namespace
{

/// orientByMinimumSpanningTree with the graph's nodes numbered in the grid's order (Index: 32 bits where they fit),
/// so that a node's neighbours lie near it in memory. Every choice (the components' seeds, the order in which a
/// component is collected, the queue's order) is still made on the points' original indices, so the orientation is
/// the one of the original numbering, bit for bit.
template <typename Index>
bool orientInGridOrder(NeighborGrid& grid, std::size_t n, int graphNeighbors, double* normals,
  const ParallelOptions& parallel, std::size_t& components, const int* degrees)
{
  const GridView& g = grid.view();
  const std::size_t count = g.count;
  const Index none = std::numeric_limits<Index>::max();

  // Each node's out-degree (graphNeighbors, or its own larger count) and its slots in `nearest`.
  std::vector<std::size_t> slot(count + 1, 0);
  for (std::size_t s = 0; s < count; ++s)
  {
    const int d = degrees ? std::max(graphNeighbors, degrees[g.ids[s]]) : graphNeighbors;
    slot[s + 1] = slot[s] + static_cast<std::size_t>(std::max(d, 1));
  }
  std::vector<Index> nearest(slot[count], none); // the nearest other nodes of each node
  const int threads = resolveThreadCount(parallel.threads);
  std::vector<std::vector<std::pair<double, std::uint64_t>>> knn(static_cast<std::size_t>(threads));
  const ParallelOptions queryStage = progressStage(parallel, 0.0, 0.4);
  const bool queried = parallelFor(count, queryStage, [&](std::size_t begin, std::size_t end, int t) {
    for (std::size_t s = begin; s < end; ++s)
    {
      const std::size_t k = slot[s + 1] - slot[s];
      grid.kNearest(g.points[s], static_cast<int>(k) + 1, knn[t]);
      std::size_t j = 0;
      for (const auto& c : knn[t])
      {
        if (c.second != s && j < k)
        {
          nearest[slot[s] + j++] = static_cast<Index>(c.second);
        }
      }
    }
  });
  if (!queried)
  {
    return false;
  }
  // The grid's cells are no longer needed: keep its nodes' positions and original indices, and the normals in the
  // same order.
  std::vector<Vec3> position(g.points, g.points + count);
  std::vector<std::uint64_t> original(g.ids, g.ids + count);
  grid = NeighborGrid();
  std::vector<Vec3> normal(count);
  for (std::size_t s = 0; s < count; ++s)
  {
    const double* ni = normals + 3 * original[s];
    normal[s] = { ni[0], ni[1], ni[2] };
  }

  // Symmetric adjacency in CSR form, each list sorted by original index and without repeats.
  std::vector<std::size_t> start(count + 1, 0);
  for (std::size_t s = 0; s < count; ++s)
  {
    for (std::size_t j = slot[s]; j < slot[s + 1] && nearest[j] != none; ++j)
    {
      ++start[s + 1];
      ++start[static_cast<std::size_t>(nearest[j]) + 1];
    }
  }
  for (std::size_t s = 0; s < count; ++s)
  {
    start[s + 1] += start[s];
  }
  if (parallel.progress && parallel.progress(0.4))
  {
    return false;
  }
  std::vector<Index> adjacency(start[count]);
  for (std::size_t s = 0; s < count; ++s)
  {
    for (std::size_t j = slot[s]; j < slot[s + 1] && nearest[j] != none; ++j)
    {
      const Index v = nearest[j];
      adjacency[start[s]++] = v;
      adjacency[start[v]++] = static_cast<Index>(s);
    }
  }
  restoreBucketStarts(start);
  std::vector<Index>().swap(nearest);
  std::vector<std::size_t>().swap(slot);
  std::vector<Index> kept(count, 0);
  ParallelOptions sortOptions = progressStage(parallel, 0.4, 0.5);
  sortOptions.chunk = 4096;
  const auto byOriginal = [&original](Index a, Index b) { return original[a] < original[b]; };
  const bool sorted = parallelFor(count, sortOptions, [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t u = begin; u < end; ++u)
    {
      auto first = adjacency.begin() + static_cast<std::ptrdiff_t>(start[u]);
      auto last = adjacency.begin() + static_cast<std::ptrdiff_t>(start[u + 1]);
      std::sort(first, last, byOriginal);
      kept[u] = static_cast<Index>(std::unique(first, last) - first);
    }
  });
  if (!sorted)
  {
    return false;
  }
  std::size_t write = 0;
  for (std::size_t u = 0; u < count; ++u)
  {
    const std::size_t from = start[u];
    start[u] = write;
    std::copy(adjacency.begin() + static_cast<std::ptrdiff_t>(from),
      adjacency.begin() + static_cast<std::ptrdiff_t>(from + kept[u]),
      adjacency.begin() + static_cast<std::ptrdiff_t>(write));
    write += kept[u];
  }
  start[count] = write;
  adjacency.resize(write);
  adjacency.shrink_to_fit();
  std::vector<Index>().swap(kept);

  // The node of each original index (none for the points left out of the graph).
  std::vector<Index> nodeOf(n, none);
  for (std::size_t s = 0; s < count; ++s)
  {
    nodeOf[original[s]] = static_cast<Index>(s);
  }
  auto agreement = [&](Index a, Index b) { return dot(normal[a], normal[b]); };
  auto cost = [&](Index a, Index b) { return 1.0 - std::abs(agreement(a, b)); };
  auto flip = [&](Index a, double sign) {
    if (sign < 0.0)
    {
      normal[a] = { -normal[a].x, -normal[a].y, -normal[a].z };
    }
  };

  // A queue entry: cost, then the node's and its parent's original indices (the order of the original numbering),
  // then their nodes.
  struct Entry
  {
    double cost;
    std::uint64_t node, parent;
    Index nodeIndex, parentIndex;
    bool operator>(const Entry& o) const
    {
      return std::tie(cost, node, parent) > std::tie(o.cost, o.node, o.parent);
    }
  };
  std::vector<unsigned char> visited(count, 0);
  std::vector<Index> component;
  std::size_t oriented = 0, popped = 0;
  for (std::size_t seed = 0; seed < n; ++seed)
  {
    const Index root0 = nodeOf[seed];
    if (root0 == none || visited[root0])
    {
      continue;
    }
    // Collect the component (breadth first) and pick its root: the point farthest from its centroid.
    component.assign(1, root0);
    visited[root0] = 1;
    for (std::size_t head = 0; head < component.size(); ++head)
    {
      const Index u = component[head];
      for (std::size_t e = start[u]; e < start[u + 1]; ++e)
      {
        const Index v = adjacency[e];
        if (!visited[v])
        {
          visited[v] = 1;
          component.push_back(v);
        }
      }
    }
    double centroid[3] = { 0, 0, 0 };
    for (Index u : component)
    {
      const double p[3] = { position[u].x, position[u].y, position[u].z };
      for (int a = 0; a < 3; ++a)
      {
        centroid[a] += p[a] / static_cast<double>(component.size());
      }
    }
    Index root = component[0];
    double farthest = -1.0;
    for (Index u : component)
    {
      const double p[3] = { position[u].x, position[u].y, position[u].z };
      double d2 = 0.0;
      for (int a = 0; a < 3; ++a)
      {
        d2 += (p[a] - centroid[a]) * (p[a] - centroid[a]);
      }
      if (d2 > farthest)
      {
        farthest = d2;
        root = u;
      }
    }
    const double r[3] = { position[root].x, position[root].y, position[root].z };
    const double nr[3] = { normal[root].x, normal[root].y, normal[root].z };
    double outward = 0.0;
    for (int a = 0; a < 3; ++a)
    {
      outward += nr[a] * (r[a] - centroid[a]);
    }
    flip(root, outward);

    // Prim's algorithm from the root; each node takes the orientation of the tree node that reached it.
    for (Index u : component)
    {
      visited[u] = 0;
    }
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> frontier;
    frontier.push({ 0.0, original[root], original[root], root, root });
    while (!frontier.empty())
    {
      const Entry top = frontier.top();
      frontier.pop();
      // Progress per 65536 entries taken from the queue (the stale ones after the last node included).
      if (++popped % 65536 == 0 && parallel.progress &&
        parallel.progress(0.5 + 0.5 * static_cast<double>(oriented) / static_cast<double>(count)))
      {
        return false;
      }
      const Index u = top.nodeIndex;
      if (visited[u])
      {
        continue;
      }
      visited[u] = 1;
      ++oriented;
      if (u != top.parentIndex)
      {
        flip(u, agreement(top.parentIndex, u));
      }
      for (std::size_t e = start[u]; e < start[u + 1]; ++e)
      {
        const Index v = adjacency[e];
        if (!visited[v])
        {
          frontier.push({ cost(u, v), original[v], original[u], v, u });
        }
      }
    }
    ++components;
  }
  for (std::size_t s = 0; s < count; ++s)
  {
    double* ni = normals + 3 * original[s];
    ni[0] = normal[s].x;
    ni[1] = normal[s].y;
    ni[2] = normal[s].z;
  }
  return true;
}

} // namespace

bool orientByMinimumSpanningTree(const double* xyz, std::size_t n, int graphNeighbors, double* normals,
  const ParallelOptions& parallel, std::size_t& components, const int* degrees)
{
  components = 0;
  // Graph nodes: points with a finite position and a finite normal.
  std::vector<unsigned char> usable(n, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    usable[i] = finite3(xyz + 3 * i) && finite3(normals + 3 * i);
  }
  NeighborGrid grid;
  grid.build(xyz, nullptr, n, NeighborGrid::suggestCellSizeForKNearest(xyz, n, graphNeighbors + 1), usable.data());
  std::vector<unsigned char>().swap(usable);
  // Node indices of 32 bits where every node and the "none" mark fit (half the graph's memory).
  if (grid.view().count < std::numeric_limits<std::uint32_t>::max())
  {
    return orientInGridOrder<std::uint32_t>(grid, n, graphNeighbors, normals, parallel, components, degrees);
  }
  return orientInGridOrder<std::uint64_t>(grid, n, graphNeighbors, normals, parallel, components, degrees);
}

} // namespace gls
