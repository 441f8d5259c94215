#include "MinimumSpanningOrientation.h"

#include "OrientationEdges.h"
#include "SignedSpanningForest.h"

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

/// The nearest-other lists of every node (nearestLists): which nodes are, each node's degree in the graph, which
/// stored lists answer, and the queries of the others.
template <typename Index>
class NearestListBuilder
{
public:
  static constexpr Index kNone = std::numeric_limits<Index>::max();

  NearestListBuilder(const OrientationGraph& graph, NearestLists<Index>& lists)
    : Graph(graph)
    , G(graph.grid->view())
    , Width(static_cast<std::size_t>(std::max(graph.graphNeighbors, 1)))
    , Lists(lists)
  {
  }

  bool isNode(std::size_t s) const { return this->Graph.nodes == nullptr || this->Graph.nodes[s] != 0; }

  /// A node's k in the tree's graph (at least the graph's width).
  std::size_t degreeOf(std::size_t s) const
  {
    const int d = this->Graph.sortedDegrees ? this->Graph.sortedDegrees[s] : 0;
    return std::max(this->Width, static_cast<std::size_t>(std::max(d, 0)));
  }

  /// The nodes whose stored list is not their answer (incomplete, holding a point that is not a node, or a node
  /// that needs more than the graph's width), in order; their extra storage is laid out. The other lists lose
  /// nothing; a point that is no node gets an empty list.
  std::vector<Index> listsToQuery(int threads)
  {
    const std::size_t count = this->G.count;
    std::vector<unsigned char> queried(count, 0);
    ParallelOptions checkOptions;
    checkOptions.threads = threads;
    checkOptions.chunk = 65536;
    parallelFor(count, checkOptions, [&](std::size_t begin, std::size_t end, int) {
      for (std::size_t s = begin; s < end; ++s)
      {
        Index* row = this->Lists.fixed.data() + s * this->Width;
        if (!this->isNode(s))
        {
          std::fill(row, row + this->Width, kNone);
          continue;
        }
        bool complete = this->degreeOf(s) == this->Width;
        for (std::size_t j = 0; complete && j < this->Width; ++j)
        {
          complete = row[j] != kNone && this->isNode(row[j]);
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
        if (this->degreeOf(s) > this->Width)
        {
          this->Lists.extraNodes.push_back(static_cast<Index>(s));
          this->Lists.extraStart.push_back(this->Lists.extraStart.back() + this->degreeOf(s) - this->Width);
        }
      }
    }
    this->Lists.extra.assign(this->Lists.extraStart.back(), kNone);
    return ask;
  }

  /// The lists of the nodes in `ask`, from k-nearest queries among the nodes. False if aborted.
  bool query(const std::vector<Index>& ask, const ParallelOptions& parallel)
  {
    const int threads = resolveThreadCount(parallel.threads);
    std::vector<std::vector<std::pair<double, std::uint64_t>>> knn(static_cast<std::size_t>(threads));
    return parallelFor(ask.size(), parallel, [&](std::size_t begin, std::size_t end, int t) {
      for (std::size_t a = begin; a < end; ++a)
      {
        this->queryList(ask[a], knn[static_cast<std::size_t>(t)]);
      }
    });
  }

private:
  /// Node s's list (and its extra storage past the graph's width) from its k-nearest nodes but itself.
  void queryList(std::size_t s, std::vector<std::pair<double, std::uint64_t>>& knn)
  {
    const std::size_t d = this->degreeOf(s);
    this->Graph.grid->kNearest(this->G.points[s], static_cast<int>(d) + 1, knn, this->Graph.nodes);
    Index* row = this->Lists.fixed.data() + s * this->Width;
    std::fill(row, row + this->Width, kNone);
    Index* more = nullptr;
    if (d > this->Width)
    {
      const auto e =
        std::lower_bound(this->Lists.extraNodes.begin(), this->Lists.extraNodes.end(), static_cast<Index>(s));
      const std::size_t extraIndex = static_cast<std::size_t>(e - this->Lists.extraNodes.begin());
      more = this->Lists.extra.data() + this->Lists.extraStart[extraIndex];
    }
    std::size_t j = 0;
    for (const auto& c : knn)
    {
      if (c.second != s && j < d)
      {
        (j < this->Width ? row[j] : more[j - this->Width]) = static_cast<Index>(c.second);
        ++j;
      }
    }
  }

  const OrientationGraph& Graph;
  const GridView& G;
  const std::size_t Width;
  NearestLists<Index>& Lists;
};

/// The nearest-other lists of every node: those the caller's earlier query completed are kept, the others (lists
/// that are incomplete, hold a point that is not a node, or nodes that need more than the graph's k) are queried on
/// the grid among the nodes. False if aborted.
template <typename Index>
bool nearestLists(OrientationGraph& graph, NearestLists<Index>& lists, const ParallelOptions& parallel)
{
  const std::size_t count = graph.grid->view().count;
  const std::size_t width = static_cast<std::size_t>(std::max(graph.graphNeighbors, 1));
  lists.width = width;
  if constexpr (std::is_same_v<Index, std::uint32_t>)
  {
    lists.fixed = std::move(graph.nearestOthers);
  }
  if (lists.fixed.size() != count * width)
  {
    lists.fixed.assign(count * width, NearestListBuilder<Index>::kNone);
  }
  NearestListBuilder<Index> builder(graph, lists);
  return builder.query(builder.listsToQuery(parallel.threads), parallel);
}

/// The cost of the edge between two normals: 1 - |n_a . n_b| (the same for either order and either sign).
inline double edgeCost(const Vec3& a, const Vec3& b)
{
  return 1.0 - std::abs(dot(a, b));
}

/// Orients each tree of the signed forest (a connected component of the graph): from its node farthest from its
/// centroid, turned away from the centroid, every node agrees with its neighbours along the tree. Then, where the
/// cloud is terrain-like (flat, kTerrainFlatness, with coherent normals, kTerrainCoherence), each component whose
/// mean z is below -kTerrainCoherence is turned over, to face +z; pieces of a closed surface keep their sides.
/// With an up direction (UpAlongSpanningTree) instead: each component is turned so that the sum of n . up over its
/// upward nodes (|n . up| >= kUpAnchorCosine) is positive (one without any keeps the outward rule), then every upward
/// node faces up on its own. GroundUpAlongSpanningTree: each component is turned so that the sum of n . up over its
/// ground nodes (the lowest near-horizontal ones of each column of the cloud) is positive; nothing more. The
/// components are numbered in the order of their lowest original index and their sums
/// run in the original order of their points, so the result does not depend on the grid's numbering.
template <typename Index>
class ComponentOrientation
{
public:
  /// nodeOf: the node of each original index (none for the points that are not nodes).
  ComponentOrientation(const GridView& g, const std::vector<Index>& nodeOf, const SignedForest<Index>& forest,
    Vec3* normal, NormalOrientation rule, const Vec3& up)
    : G(g)
    , NodeOf(nodeOf)
    , Forest(forest)
    , Normal(normal)
    , Rule(rule)
    , Up(up)
    , Slot(g.count, std::numeric_limits<Index>::max())
  {
  }

  /// Orients every component; returns their count.
  std::size_t orient(const ParallelOptions& parallel)
  {
    this->Number();
    this->ChooseRoots();
    if (this->Rule == NormalOrientation::UpAlongSpanningTree)
    {
      this->TurnBy([](const Vec3&, double u) { return std::abs(u) >= kUpAnchorCosine; });
    }
    else if (this->Rule == NormalOrientation::GroundUpAlongSpanningTree)
    {
      this->TurnByGround();
    }
    this->Apply(parallel, [this](std::size_t s, const Component& c) { return (this->Forest.turned[s] ^ c.turn) != 0; });
    if (this->Rule == NormalOrientation::UpAlongSpanningTree)
    {
      this->FaceUpOneByOne(parallel);
    }
    else if (this->Rule == NormalOrientation::MinimumSpanningTree && this->Flat())
    {
      this->FaceUpIfTerrain(parallel);
    }
    return this->Components.size();
  }

private:
  struct Component
  {
    double sum[3] = { 0.0, 0.0, 0.0 }; ///< of the positions; then the centroid
    double size = 0.0;
    double farthest = -1.0;            ///< the largest squared distance to the centroid
    Index root = 0;                    ///< the node at that distance (the first in the original order)
    unsigned char turn = 0;            ///< 1: the tree's node (Forest.tree) is turned over
    double z = 0.0;                    ///< the sum of the oriented normals' z
  };

  Component& Of(Index s) { return this->Components[this->Slot[this->Forest.tree[s]]]; }

  /// The components in the order of their lowest original index, with their centroids.
  void Number()
  {
    const Index none = std::numeric_limits<Index>::max();
    for (const Index s : this->NodeOf)
    {
      if (s == none)
      {
        continue;
      }
      Index& slot = this->Slot[this->Forest.tree[s]];
      if (slot == none)
      {
        slot = static_cast<Index>(this->Components.size());
        this->Components.emplace_back();
      }
      Component& c = this->Components[slot];
      const Vec3& p = this->G.points[s];
      c.sum[0] += p.x;
      c.sum[1] += p.y;
      c.sum[2] += p.z;
      c.size += 1.0;
    }
    for (Component& c : this->Components)
    {
      for (double& v : c.sum)
      {
        v /= c.size;
      }
    }
  }

  /// Each component's point farthest from its centroid (of equally far ones, the lowest original index: the grid's
  /// order is walked, for its memory access), and whether its tree must turn over for that point's normal to face
  /// away from the centroid.
  void ChooseRoots()
  {
    const Index none = std::numeric_limits<Index>::max();
    for (std::size_t s = 0; s < this->G.count; ++s)
    {
      const Index slot = this->Slot[this->Forest.tree[s]];
      if (slot == none)
      {
        continue;
      }
      Component& c = this->Components[slot];
      const Vec3& p = this->G.points[s];
      const double d[3] = { p.x - c.sum[0], p.y - c.sum[1], p.z - c.sum[2] };
      const double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      if (d2 > c.farthest || (d2 == c.farthest && this->G.ids[s] < this->G.ids[c.root]))
      {
        c.farthest = d2;
        c.root = static_cast<Index>(s);
      }
    }
    for (Component& c : this->Components)
    {
      const Vec3& r = this->G.points[c.root];
      const Vec3& n = this->Normal[c.root];
      const double outward = n.x * (r.x - c.sum[0]) + n.y * (r.y - c.sum[1]) + n.z * (r.z - c.sum[2]);
      c.turn = static_cast<unsigned char>(this->Forest.turned[c.root] ^ (outward < 0.0 ? 1 : 0));
    }
  }

  /// Turns over each node s (of a component c) where turn(s, c) is true. A point that is not a node is a tree of its
  /// own (it has no edge) that no component numbered.
  template <typename Turn>
  void Apply(const ParallelOptions& parallel, const Turn& turn)
  {
    ParallelOptions options;
    options.threads = parallel.threads;
    options.chunk = 65536;
    const Index none = std::numeric_limits<Index>::max();
    parallelFor(this->G.count, options, [&](std::size_t begin, std::size_t end, int) {
      for (std::size_t s = begin; s < end; ++s)
      {
        const Index slot = this->Slot[this->Forest.tree[s]];
        if (slot != none && turn(s, this->Components[slot]))
        {
          Vec3& v = this->Normal[s];
          v = { -v.x, -v.y, -v.z };
        }
      }
    });
  }

  /// The turn of each component that has voting nodes (`votes(n, n . up)`: whether node s with normal n votes): their
  /// n . up summed as the tree orients them (Forest.turned), in the original order, must be positive.
  template <typename Votes>
  void TurnBy(const Votes& votes)
  {
    const Index none = std::numeric_limits<Index>::max();
    std::vector<double> vote(this->Components.size(), 0.0);
    for (const Index s : this->NodeOf)
    {
      if (s == none)
      {
        continue;
      }
      const double u = dot(this->Normal[s], this->Up);
      if (votes(this->G.points[s], u))
      {
        vote[this->Slot[this->Forest.tree[s]]] += this->Forest.turned[s] ? -u : u;
      }
    }
    for (std::size_t c = 0; c < vote.size(); ++c)
    {
      if (vote[c] != 0.0)
      {
        this->Components[c].turn = vote[c] < 0.0 ? 1 : 0;
      }
    }
  }

  /// The ground rule (see the class): the nodes whose normal is within acos(kGroundCosine) of up and whose height
  /// (along up) is within kGroundLayer of a column's side of the lowest such node of their column (a grid of
  /// kGroundColumns along the longer horizontal side of the nodes' box) vote.
  void TurnByGround()
  {
    // A horizontal frame: two directions across up.
    const Vec3 helper = std::abs(this->Up.x) < 0.9 ? Vec3{ 1.0, 0.0, 0.0 } : Vec3{ 0.0, 1.0, 0.0 };
    const Vec3 e1 = (1.0 / std::sqrt(squaredNorm(cross(this->Up, helper)))) * cross(this->Up, helper);
    const Vec3 e2 = cross(this->Up, e1);
    double low[2] = { 0.0, 0.0 }, high[2] = { 0.0, 0.0 };
    bool any = false;
    for (std::size_t s = 0; s < this->G.count; ++s)
    {
      if (this->Slot[this->Forest.tree[s]] == std::numeric_limits<Index>::max())
      {
        continue; // not a node
      }
      const double c[2] = { dot(this->G.points[s], e1), dot(this->G.points[s], e2) };
      for (int a = 0; a < 2; ++a)
      {
        low[a] = any ? std::min(low[a], c[a]) : c[a];
        high[a] = any ? std::max(high[a], c[a]) : c[a];
      }
      any = true;
    }
    const double side = std::max(high[0] - low[0], high[1] - low[1]) / kGroundColumns;
    if (!any || !(side > 0.0))
    {
      return;
    }
    const int columns = kGroundColumns + 1;
    const auto column = [&](const Vec3& p) {
      const int i = std::min(columns - 1, static_cast<int>((dot(p, e1) - low[0]) / side));
      const int j = std::min(columns - 1, static_cast<int>((dot(p, e2) - low[1]) / side));
      return static_cast<std::size_t>(i) * columns + static_cast<std::size_t>(j);
    };
    std::vector<double> lowest(static_cast<std::size_t>(columns) * columns, std::numeric_limits<double>::infinity());
    for (std::size_t s = 0; s < this->G.count; ++s)
    {
      const double u = dot(this->Normal[s], this->Up);
      if (std::abs(u) >= kGroundCosine && this->Slot[this->Forest.tree[s]] != std::numeric_limits<Index>::max())
      {
        double& l = lowest[column(this->G.points[s])];
        l = std::min(l, dot(this->G.points[s], this->Up));
      }
    }
    const double layer = kGroundLayer * side;
    this->TurnBy([&](const Vec3& p, double u) {
      return std::abs(u) >= kGroundCosine && dot(p, this->Up) <= lowest[column(p)] + layer;
    });
  }

  /// Every upward node (|n . up| >= kUpAnchorCosine) facing up.
  void FaceUpOneByOne(const ParallelOptions& parallel)
  {
    ParallelOptions options;
    options.threads = parallel.threads;
    options.chunk = 65536;
    parallelFor(this->G.count, options, [&](std::size_t begin, std::size_t end, int) {
      for (std::size_t s = begin; s < end; ++s)
      {
        Vec3& v = this->Normal[s];
        if (dot(v, this->Up) <= -kUpAnchorCosine)
        {
          v = { -v.x, -v.y, -v.z };
        }
      }
    });
  }

  /// The terrain rule (see the class).
  void FaceUpIfTerrain(const ParallelOptions& parallel)
  {
    const Index none = std::numeric_limits<Index>::max();
    for (const Index s : this->NodeOf)
    {
      if (s != none)
      {
        this->Of(s).z += this->Normal[s].z;
      }
    }
    double coherent = 0.0, total = 0.0;
    for (const Component& c : this->Components)
    {
      coherent += c.z < 0.0 ? -c.z : c.z;
      total += c.size;
    }
    if (!(coherent >= kTerrainCoherence * total))
    {
      return;
    }
    this->Apply(parallel, [](std::size_t, const Component& c) { return c.z < -kTerrainCoherence * c.size; });
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

  const GridView& G;
  const std::vector<Index>& NodeOf;
  const SignedForest<Index>& Forest;
  Vec3* Normal;
  NormalOrientation Rule; ///< how the components turn (see the class)
  Vec3 Up;                ///< the up and ground rules' direction (unit)
  std::vector<Index> Slot; ///< per tree (its Forest.tree node): its component
  std::vector<Component> Components;
};

template <typename Index>
bool orientWith(OrientationGraph& graph, Vec3* normal, const ParallelOptions& parallel, std::size_t& components)
{
  IncidentEdges<Index> edges;
  if (!nearestLists(graph, edges.lists, progressStage(parallel, 0.0, 0.4)))
  {
    return false;
  }
  graph.sortedDegrees = nullptr;
  if (graph.listsMade)
  {
    graph.listsMade();
  }
  graph.grid->releaseCells(); // the points and their ids stay: the graph's node s is the grid's point s
  const GridView& g = graph.grid->view();
  const std::size_t count = g.count;
  if (!edges.addReverse(count, progressStage(parallel, 0.4, 0.5)))
  {
    return false;
  }
  const auto cost = [normal](Index a, Index b) { return edgeCost(normal[a], normal[b]); };
  const auto differ = [normal](Index a, Index b) { return dot(normal[a], normal[b]) < 0.0; };
  SignedForest<Index> forest;
  if (!signedSpanningForest(edges, count, EdgeOrder{ g.ids }, cost, differ, forest, progressStage(parallel, 0.5, 0.95)))
  {
    return false;
  }
  edges = IncidentEdges<Index>();
  // The node of each original index (none for the points that are not nodes).
  const Index none = std::numeric_limits<Index>::max();
  std::vector<Index> nodeOf(graph.n, none);
  for (std::size_t s = 0; s < count; ++s)
  {
    if (graph.nodes == nullptr || graph.nodes[s] != 0)
    {
      nodeOf[g.ids[s]] = static_cast<Index>(s);
    }
  }
  components = ComponentOrientation<Index>(g, nodeOf, forest, normal, graph.rule, graph.up).orient(parallel);
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
