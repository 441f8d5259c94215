#include "MinimumSpanningOrientation.h"

#include "gls/NormalEstimation.h"
#include "gls/Vec3.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <utility>

namespace gls
{
namespace
{

/// Each node's nearest other nodes (directed, nearest first), numbered in the grid's order (Index: 32 bits where
/// they fit): `width` per node in `fixed`, and for the nodes that need more (their degree), the rest in `extra`,
/// [extraStart[e], extraStart[e + 1]) for extraNodes[e] (ascending). Both are padded with the largest Index where a
/// cloud has fewer other nodes than a node's degree.
template <typename Index>
struct NearestLists
{
  std::size_t width = 0;
  std::vector<Index> fixed;
  std::vector<Index> extraNodes;
  std::vector<std::size_t> extraStart{ 0 };
  std::vector<Index> extra;

  /// Calls f(v) for each of node s's nearest others, nearest first.
  template <typename F>
  void forEach(std::size_t s, F&& f) const
  {
    const Index none = std::numeric_limits<Index>::max();
    for (std::size_t j = s * width; j < (s + 1) * width && fixed[j] != none; ++j)
    {
      f(fixed[j]);
    }
    const auto e = std::lower_bound(extraNodes.begin(), extraNodes.end(), static_cast<Index>(s));
    if (e != extraNodes.end() && *e == s)
    {
      const std::size_t k = static_cast<std::size_t>(e - extraNodes.begin());
      for (std::size_t j = extraStart[k]; j < extraStart[k + 1] && extra[j] != none; ++j)
      {
        f(extra[j]);
      }
    }
  }
};

/// The nearest-other lists of every node: those the caller's earlier query completed are kept, the others (lists
/// that are incomplete, hold a point that is not a node, or nodes that need more than the graph's k) are queried on
/// the grid among the nodes. False if aborted.
template <typename Index>
bool nearestLists(OrientationGraph& graph, NearestLists<Index>& lists, const ParallelOptions& parallel)
{
  const GridView& g = graph.grid->view();
  const std::size_t count = g.count;
  const Index none = std::numeric_limits<Index>::max();
  const std::size_t width = static_cast<std::size_t>(std::max(graph.graphNeighbors, 1));
  const auto isNode = [&graph](std::size_t s) { return graph.nodes == nullptr || graph.nodes[s] != 0; };
  const auto degreeOf = [&](std::size_t s) {
    const int d = graph.sortedDegrees ? graph.sortedDegrees[s] : 0;
    return std::max(width, static_cast<std::size_t>(std::max(d, 0)));
  };
  lists.width = width;
  if constexpr (std::is_same_v<Index, std::uint32_t>)
  {
    lists.fixed = std::move(graph.nearestOthers);
  }
  if (lists.fixed.size() != count * width)
  {
    lists.fixed.assign(count * width, none);
  }

  // Which lists must be queried (the nodes whose stored list is not their answer); the others' lists lose nothing.
  std::vector<unsigned char> queried(count, 0);
  ParallelOptions checkOptions;
  checkOptions.threads = parallel.threads;
  checkOptions.chunk = 65536;
  parallelFor(count, checkOptions, [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t s = begin; s < end; ++s)
    {
      Index* row = lists.fixed.data() + s * width;
      if (!isNode(s))
      {
        std::fill(row, row + width, none);
        continue;
      }
      bool complete = degreeOf(s) == width;
      for (std::size_t j = 0; complete && j < width; ++j)
      {
        complete = row[j] != none && isNode(row[j]);
      }
      queried[s] = complete ? 0 : 1;
    }
  });
  std::vector<Index> ask;
  for (std::size_t s = 0; s < count; ++s)
  {
    if (queried[s])
    {
      ask.push_back(static_cast<Index>(s));
      if (degreeOf(s) > width)
      {
        lists.extraNodes.push_back(static_cast<Index>(s));
        lists.extraStart.push_back(lists.extraStart.back() + degreeOf(s) - width);
      }
    }
  }
  std::vector<unsigned char>().swap(queried);
  lists.extra.assign(lists.extraStart.back(), none);

  const int threads = resolveThreadCount(parallel.threads);
  std::vector<std::vector<std::pair<double, std::uint64_t>>> knn(static_cast<std::size_t>(threads));
  return parallelFor(ask.size(), parallel, [&](std::size_t begin, std::size_t end, int t) {
    for (std::size_t a = begin; a < end; ++a)
    {
      const std::size_t s = ask[a];
      const std::size_t d = degreeOf(s);
      graph.grid->kNearest(g.points[s], static_cast<int>(d) + 1, knn[t], graph.nodes);
      Index* row = lists.fixed.data() + s * width;
      std::fill(row, row + width, none);
      Index* more = nullptr;
      if (d > width)
      {
        const auto e = std::lower_bound(lists.extraNodes.begin(), lists.extraNodes.end(), static_cast<Index>(s));
        more = lists.extra.data() + lists.extraStart[static_cast<std::size_t>(e - lists.extraNodes.begin())];
      }
      std::size_t j = 0;
      for (const auto& c : knn[t])
      {
        if (c.second != s && j < d)
        {
          (j < width ? row[j] : more[j - width]) = static_cast<Index>(c.second);
          ++j;
        }
      }
    }
  });
}

/// The symmetric adjacency of the directed lists in CSR form (start: count + 1 offsets), each node's list sorted by
/// original index and without repeats. Frees the lists. False if aborted.
template <typename Index>
bool symmetricAdjacency(NearestLists<Index>& lists, const std::uint64_t* original, std::size_t count,
  std::vector<std::size_t>& start, std::vector<Index>& adjacency, const ParallelOptions& parallel)
{
  start.assign(count + 1, 0);
  for (std::size_t s = 0; s < count; ++s)
  {
    lists.forEach(s, [&](Index v) {
      ++start[s + 1];
      ++start[static_cast<std::size_t>(v) + 1];
    });
  }
  for (std::size_t s = 0; s < count; ++s)
  {
    start[s + 1] += start[s];
  }
  adjacency.resize(start[count]);
  for (std::size_t s = 0; s < count; ++s)
  {
    lists.forEach(s, [&](Index v) {
      adjacency[start[s]++] = v;
      adjacency[start[v]++] = static_cast<Index>(s);
    });
  }
  restoreBucketStarts(start);
  lists = NearestLists<Index>();
  std::vector<Index> kept(count, 0);
  ParallelOptions sortOptions = parallel;
  sortOptions.chunk = 4096;
  const auto byOriginal = [original](Index a, Index b) { return original[a] < original[b]; };
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
  return true;
}

/// The order of the graph's edges: by cost, then by the lower and the higher original index of their ends. It is
/// strict, so the minimum spanning forest is unique: the same whatever the numbering and the thread count.
struct EdgeKey
{
  double cost;
  std::uint64_t low, high;

  bool operator<(const EdgeKey& o) const
  {
    return cost != o.cost ? cost < o.cost : (low != o.low ? low < o.low : high < o.high);
  }
};

/// The cost of the edge between two normals: 1 - |n_a . n_b| (the same for either order and either sign).
inline double edgeCost(const Vec3& a, const Vec3& b)
{
  return 1.0 - std::abs(dot(a, b));
}

/// The minimum spanning forest of the CSR graph (Boruvka: each round, every tree of the forest takes its cheapest
/// edge to another tree; the rounds' scans run in parallel), as a CSR adjacency of its edges. False if aborted.
template <typename Index>
bool spanningForest(const GridView& g, const std::vector<std::size_t>& start, const std::vector<Index>& adjacency,
  const Vec3* normal, std::vector<std::size_t>& forestStart, std::vector<Index>& forest,
  const ParallelOptions& parallel)
{
  const std::size_t count = g.count;
  const Index none = std::numeric_limits<Index>::max();
  const auto key = [&](Index a, Index b) {
    const std::uint64_t oa = g.ids[a], ob = g.ids[b];
    return EdgeKey{ edgeCost(normal[a], normal[b]), std::min(oa, ob), std::max(oa, ob) };
  };
  std::vector<Index> tree(count); // each node's tree, as one of its nodes (union-find, path halving)
  for (std::size_t s = 0; s < count; ++s)
  {
    tree[s] = static_cast<Index>(s);
  }
  const auto find = [&tree](Index a) {
    while (tree[a] != a)
    {
      tree[a] = tree[tree[a]];
      a = tree[a];
    }
    return a;
  };
  std::vector<Index> label(tree);  // each node's tree at the start of the round
  std::vector<Index> cheapest(count, none); // per node: the other end of its cheapest edge out of its tree
  std::vector<Index> from(count, none);     // per tree (its label): the node of its cheapest edge out
  std::vector<std::pair<Index, Index>> edges;
  ParallelOptions scan;
  scan.threads = parallel.threads;
  scan.chunk = 4096;
  for (int round = 0;; ++round)
  {
    if (parallel.progress && parallel.progress(std::min(0.9, 0.15 * round)))
    {
      return false;
    }
    parallelFor(count, scan, [&](std::size_t begin, std::size_t end, int) {
      for (std::size_t u = begin; u < end; ++u)
      {
        Index best = none;
        EdgeKey bestKey{};
        for (std::size_t e = start[u]; e < start[u + 1]; ++e)
        {
          const Index v = adjacency[e];
          if (label[v] == label[u])
          {
            continue;
          }
          const EdgeKey k = key(static_cast<Index>(u), v);
          if (best == none || k < bestKey)
          {
            best = v;
            bestKey = k;
          }
        }
        cheapest[u] = best;
      }
    });
    // Each tree's cheapest edge out (the strict order makes it one edge, whatever the order of this loop).
    std::fill(from.begin(), from.end(), none);
    for (std::size_t u = 0; u < count; ++u)
    {
      if (cheapest[u] == none)
      {
        continue;
      }
      Index& f = from[label[u]];
      if (f == none || key(static_cast<Index>(u), cheapest[u]) < key(f, cheapest[f]))
      {
        f = static_cast<Index>(u);
      }
    }
    bool merged = false;
    for (std::size_t t = 0; t < count; ++t)
    {
      const Index u = from[t];
      if (u == none)
      {
        continue;
      }
      const Index a = find(u), b = find(cheapest[u]);
      if (a != b) // two trees that chose the same edge add it once
      {
        tree[std::max(a, b)] = std::min(a, b);
        edges.emplace_back(u, cheapest[u]);
        merged = true;
      }
    }
    if (!merged)
    {
      break;
    }
    for (std::size_t s = 0; s < count; ++s)
    {
      label[s] = find(static_cast<Index>(s));
    }
  }
  forestStart.assign(count + 1, 0);
  for (const auto& e : edges)
  {
    ++forestStart[static_cast<std::size_t>(e.first) + 1];
    ++forestStart[static_cast<std::size_t>(e.second) + 1];
  }
  for (std::size_t s = 0; s < count; ++s)
  {
    forestStart[s + 1] += forestStart[s];
  }
  forest.resize(forestStart[count]);
  for (const auto& e : edges)
  {
    forest[forestStart[e.first]++] = e.second;
    forest[forestStart[e.second]++] = e.first;
  }
  restoreBucketStarts(forestStart);
  return true;
}

/// Orients one connected component after the other: from its point farthest from its centroid (oriented away from
/// it), each node takes the orientation of its parent in the minimum spanning forest.
template <typename Index>
class TreePropagation
{
public:
  TreePropagation(const GridView& g, const std::vector<std::size_t>& start, const std::vector<Index>& adjacency,
    const std::vector<std::size_t>& forestStart, const std::vector<Index>& forest, Vec3* normal)
    : G(g)
    , Start(start)
    , Adjacency(adjacency)
    , ForestStart(forestStart)
    , Forest(forest)
    , Normal(normal)
    , Visited(g.count, 0)
  {
  }

  /// Orients the component of `seed` (a node not yet reached).
  void orientComponent(Index seed)
  {
    this->Collect(seed);
    this->Propagate(this->Root());
    double z = 0.0;
    for (Index u : this->Component)
    {
      z += this->Normal[u].z;
    }
    this->Components.push_back({ seed, z, static_cast<double>(this->Component.size()) });
  }

  /// Once every component is oriented: where the cloud is terrain-like (flat, kTerrainFlatness, with coherent normals,
  /// kTerrainCoherence), each component whose mean z is below -kTerrainCoherence is turned over, to face +z. Pieces of
  /// a closed surface keep their sides.
  void faceUpIfTerrain()
  {
    double coherent = 0.0, total = 0.0;
    for (const Oriented& c : this->Components)
    {
      coherent += c.z < 0.0 ? -c.z : c.z;
      total += c.size;
    }
    if (!(coherent >= kTerrainCoherence * total) || !this->Flat())
    {
      return;
    }
    for (const Oriented& c : this->Components)
    {
      if (c.z < -kTerrainCoherence * c.size)
      {
        this->Flip(c.seed, -1.0);
        this->BreadthFirst(c.seed, this->ForestStart, this->Forest, 3, [this](Index, Index node) {
          this->Flip(node, -1.0);
        });
      }
    }
  }

  bool Reached(Index s) const { return this->Visited[s] != 0; }

private:
  double Agreement(Index a, Index b) const { return dot(this->Normal[a], this->Normal[b]); }

  void Flip(Index a, double sign)
  {
    if (sign < 0.0)
    {
      this->Normal[a] = { -this->Normal[a].x, -this->Normal[a].y, -this->Normal[a].z };
    }
  }

  /// Breadth first from `seed` over a CSR graph, into Component: each node reached for the first time (its mark
  /// below `mark`) gets the mark and reached(parent, node) is called.
  template <typename Reached>
  void BreadthFirst(Index seed, const std::vector<std::size_t>& start, const std::vector<Index>& adjacency,
    unsigned char mark, Reached&& reached)
  {
    this->Component.assign(1, seed);
    this->Visited[seed] = mark;
    for (std::size_t head = 0; head < this->Component.size(); ++head)
    {
      const Index u = this->Component[head];
      for (std::size_t e = start[u]; e < start[u + 1]; ++e)
      {
        const Index v = adjacency[e];
        if (this->Visited[v] < mark)
        {
          this->Visited[v] = mark;
          reached(u, v);
          this->Component.push_back(v);
        }
      }
    }
  }

  /// The component of `seed` in the graph (marks its nodes 1).
  void Collect(Index seed)
  {
    this->BreadthFirst(seed, this->Start, this->Adjacency, 1, [](Index, Index) {});
  }

  /// The component's point farthest from its centroid, oriented away from the centroid.
  Index Root()
  {
    double centroid[3] = { 0, 0, 0 };
    const double size = static_cast<double>(this->Component.size());
    for (Index u : this->Component)
    {
      const Vec3& p = this->G.points[u];
      centroid[0] += p.x / size;
      centroid[1] += p.y / size;
      centroid[2] += p.z / size;
    }
    Index root = this->Component[0];
    double farthest = -1.0;
    for (Index u : this->Component)
    {
      const Vec3& p = this->G.points[u];
      const double d[3] = { p.x - centroid[0], p.y - centroid[1], p.z - centroid[2] };
      const double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      if (d2 > farthest)
      {
        farthest = d2;
        root = u;
      }
    }
    const Vec3& r = this->G.points[root];
    const Vec3& nr = this->Normal[root];
    this->Flip(root, nr.x * (r.x - centroid[0]) + nr.y * (r.y - centroid[1]) + nr.z * (r.z - centroid[2]));
    return root;
  }

  /// True when the cloud is a tile of terrain in its shape: its height (z extent) at most kTerrainFlatness times its
  /// smaller horizontal extent. (A closed shape whose top and bottom the graph separates has coherent normals too.)
  bool Flat() const
  {
    if (this->G.count == 0)
    {
      return false;
    }
    Vec3 low = this->G.points[0], high = low;
    for (std::uint64_t s = 1; s < this->G.count; ++s)
    {
      const Vec3& p = this->G.points[s];
      low = { std::min(low.x, p.x), std::min(low.y, p.y), std::min(low.z, p.z) };
      high = { std::max(high.x, p.x), std::max(high.y, p.y), std::max(high.z, p.z) };
    }
    return high.z - low.z <= kTerrainFlatness * std::min(high.x - low.x, high.y - low.y);
  }

  /// Along the forest from the root: each node agrees with its parent (marks the component's nodes 2).
  void Propagate(Index root)
  {
    this->BreadthFirst(root, this->ForestStart, this->Forest, 2,
      [this](Index parent, Index node) { this->Flip(node, this->Agreement(parent, node)); });
  }

  const GridView& G;
  const std::vector<std::size_t>& Start;
  const std::vector<Index>& Adjacency;
  const std::vector<std::size_t>& ForestStart;
  const std::vector<Index>& Forest;
  Vec3* Normal;
  std::vector<unsigned char> Visited;
  std::vector<Index> Component;
  /// Each oriented component: where it was seeded, the sum of its normals' z and its size.
  struct Oriented
  {
    Index seed;
    double z;
    double size;
  };
  std::vector<Oriented> Components;
};

template <typename Index>
bool orientWith(OrientationGraph& graph, Vec3* normal, const ParallelOptions& parallel, std::size_t& components)
{
  NearestLists<Index> lists;
  if (!nearestLists(graph, lists, progressStage(parallel, 0.0, 0.4)))
  {
    return false;
  }
  graph.grid->releaseCells(); // the points and their ids stay: the graph's node s is the grid's point s
  const GridView& g = graph.grid->view();
  const std::size_t count = g.count;
  std::vector<std::size_t> start;
  std::vector<Index> adjacency;
  if ((parallel.progress && parallel.progress(0.4)) ||
    !symmetricAdjacency(lists, g.ids, count, start, adjacency, progressStage(parallel, 0.4, 0.5)))
  {
    return false;
  }
  // The node of each original index (none for the points that are not nodes): components are seeded in the
  // original order.
  const Index none = std::numeric_limits<Index>::max();
  std::vector<Index> nodeOf(graph.n, none);
  for (std::size_t s = 0; s < count; ++s)
  {
    if (graph.nodes == nullptr || graph.nodes[s] != 0)
    {
      nodeOf[g.ids[s]] = static_cast<Index>(s);
    }
  }
  std::vector<std::size_t> forestStart;
  std::vector<Index> forest;
  if (!spanningForest(g, start, adjacency, normal, forestStart, forest, progressStage(parallel, 0.5, 0.95)))
  {
    return false;
  }
  TreePropagation<Index> tree(g, start, adjacency, forestStart, forest, normal);
  for (std::size_t seed = 0; seed < graph.n; ++seed)
  {
    const Index node = nodeOf[seed];
    if (node == none || tree.Reached(node))
    {
      continue;
    }
    tree.orientComponent(node);
    ++components;
  }
  tree.faceUpIfTerrain();
  return true;
}

} // namespace

bool orientAlongSpanningTree(
  OrientationGraph& graph, Vec3* sortedNormals, const ParallelOptions& parallel, std::size_t& components)
{
  components = 0;
  // Node indices of 32 bits where every node and the "none" mark fit (half the graph's memory).
  if (graph.grid->view().count < std::numeric_limits<std::uint32_t>::max())
  {
    return orientWith<std::uint32_t>(graph, sortedNormals, parallel, components);
  }
  graph.nearestOthers.clear();
  return orientWith<std::uint64_t>(graph, sortedNormals, parallel, components);
}

} // namespace gls
