// The minimum spanning forest of the orientation's graph, kept not as edges but as what the orientation needs of it:
// each node's tree (a node standing for it) and whether the node's normal must be turned over to agree with that
// node's along the forest (Hoppe's propagation, each normal made to agree with its neighbour's along the tree's edges,
// without walking the tree). Built in Boruvka's rounds (each tree takes its cheapest edge to another tree; the scans
// run in parallel) under a strict order of the edges, so the forest and the signs do not depend on the numbering,
// the order of the edges or the thread count.
#pragma once

#include "OrientationEdges.h"

#include "gls/ParallelFor.h"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

namespace gls
{

/// Per node of a graph: its tree of the minimum spanning forest and its sign relative to the tree.
template <typename Index>
struct SignedForest
{
  std::vector<Index> tree;             ///< the node standing for the node's tree (the same for the whole tree)
  std::vector<unsigned char> turned;   ///< 1 where the node's normal must be turned over to agree with tree's node
};

/// The union-find of Boruvka's merges, kept in the forest's own arrays: each node's parent in forest.tree (always a
/// lower node: a set's root is its lowest node) and its sign relative to it in forest.turned. flatten() makes every
/// entry the node's root and its sign relative to it, the forest's meaning.
template <typename Index>
class SignedUnionFind
{
public:
  explicit SignedUnionFind(SignedForest<Index>& forest)
    : Parent(forest.tree)
    , Sign(forest.turned)
  {
  }

  /// The root of a's set, and a's sign relative to it (path halving).
  Index find(Index a, unsigned char& sign)
  {
    sign = 0;
    while (this->Parent[a] != a)
    {
      const Index up = this->Parent[a];
      this->Sign[a] ^= this->Sign[up];
      this->Parent[a] = this->Parent[up];
      sign ^= this->Sign[a];
      a = this->Parent[a];
    }
    return a;
  }

  /// Joins the sets of a and b so that their signs differ by `differ`; false when they are one set already.
  bool join(Index a, Index b, unsigned char differ)
  {
    unsigned char sa = 0, sb = 0;
    const Index ra = this->find(a, sa), rb = this->find(b, sb);
    if (ra == rb)
    {
      return false;
    }
    const Index low = std::min(ra, rb), high = std::max(ra, rb);
    this->Parent[high] = low;
    this->Sign[high] = static_cast<unsigned char>(sa ^ sb ^ differ);
    return true;
  }

  /// Every node's entry made its root and its sign relative to it: in ascending order, each node's parent (a lower
  /// node) is already its root's.
  void flatten()
  {
    for (std::size_t s = 0; s < this->Parent.size(); ++s)
    {
      const Index up = this->Parent[s];
      if (up != s)
      {
        this->Sign[s] ^= this->Sign[up];
        this->Parent[s] = this->Parent[up];
      }
    }
  }

private:
  std::vector<Index>& Parent;
  std::vector<unsigned char>& Sign;
};

/// The order of the graph's edges: by cost, then by the lower and the higher original index of their ends. It is
/// strict, so the minimum spanning forest is unique: the same whatever the numbering, the order of the edges and the
/// thread count.
struct EdgeOrder
{
  const std::uint64_t* ids; ///< each node's original index

  /// True when edge (a, b) of cost ca comes before edge (c, d) of cost cc.
  template <typename Index>
  bool before(double ca, Index a, Index b, double cc, Index c, Index d) const
  {
    if (ca != cc)
    {
      return ca < cc;
    }
    const std::uint64_t ia = this->ids[a], ib = this->ids[b], ic = this->ids[c], id = this->ids[d];
    const std::uint64_t lowAB = std::min(ia, ib), lowCD = std::min(ic, id);
    return lowAB != lowCD ? lowAB < lowCD : std::max(ia, ib) < std::max(ic, id);
  }
};

/// Boruvka's rounds of the signed minimum spanning forest (signedSpanningForest): per node whether it may still have
/// an edge out of its tree (a node without one never gets one again: trees only grow) and the other end of its
/// cheapest such edge (none before its first scan; its cost is computed again where compared, not stored), per tree
/// (its root, the forest.tree of its nodes) the node whose edge is the tree's cheapest. The union-find of the joins
/// lives in the forest's arrays. 14 bytes a node at 32-bit indices.
template <typename Index, typename Cost, typename Differ>
class SignedForestRounds
{
public:
  SignedForestRounds(const IncidentEdges<Index>& edges, std::size_t count, const EdgeOrder& order, const Cost& cost,
    const Differ& differ, SignedForest<Index>& forest, int threads)
    : Edges(edges)
    , Order(order)
    , EdgeCost(cost)
    , Differs(differ)
    , Forest(forest)
    , Sets(forest)
    , Done(count, 0)
    , Cheapest(count, kNone)
    , From(count)
  {
    forest.tree.resize(count);
    std::iota(forest.tree.begin(), forest.tree.end(), Index(0));
    forest.turned.assign(count, 0);
    for (auto& f : this->From)
    {
      f.store(kNone, std::memory_order_relaxed);
    }
    this->Scan.threads = threads;
    this->Scan.chunk = 4096;
  }

  /// Each node's cheapest edge out of its tree (a node without one is done), and each tree's (the strict order makes
  /// it one edge, whatever the order in which the nodes offer theirs).
  void findCheapestEdges()
  {
    parallelFor(this->Done.size(), this->Scan, [&](std::size_t begin, std::size_t end, int) {
      for (std::size_t s = begin; s < end; ++s)
      {
        const Index u = static_cast<Index>(s);
        if (this->Done[u])
        {
          continue;
        }
        if (this->cheapestOutOf(u) != kNone)
        {
          this->offerToTree(u);
        }
        else
        {
          this->Done[u] = 1;
        }
      }
    });
  }

  /// Each tree joins the tree at the other end of its cheapest edge, and every node's tree and sign follow. The trees
  /// are taken in the order of their roots; any order gives the same forest and signs (the chosen edges form a
  /// forest of the trees, whose signs along it are unique, and a root is its set's lowest node). Whether any tree
  /// was joined.
  bool joinTrees()
  {
    bool merged = false;
    for (std::size_t r = 0; r < this->From.size(); ++r)
    {
      std::atomic<Index>& f = this->From[r];
      const Index u = f.load(std::memory_order_relaxed);
      if (u != kNone)
      {
        merged = this->Sets.join(u, this->Cheapest[u], this->Differs(u, this->Cheapest[u]) ? 1 : 0) || merged;
        f.store(kNone, std::memory_order_relaxed);
      }
    }
    if (merged)
    {
      this->Sets.flatten();
    }
    return merged;
  }

private:
  static constexpr Index kNone = std::numeric_limits<Index>::max();

  /// Node u's cheapest edge out of its tree (its other end, kNone without one). The node's edges out of its tree only
  /// become fewer: where last round's cheapest is still out, it is still the cheapest; else all its edges are scanned.
  Index cheapestOutOf(Index u)
  {
    const Index tree = this->Forest.tree[u];
    Index best = this->Cheapest[u];
    if (best != kNone && this->Forest.tree[best] != tree)
    {
      return best;
    }
    best = kNone;
    double bestCost = 0.0;
    this->Edges.forEach(u, [&](Index v) {
      if (this->Forest.tree[v] == tree)
      {
        return;
      }
      const double c = this->EdgeCost(u, v);
      if (best == kNone || this->Order.before(c, u, v, bestCost, u, best))
      {
        best = v;
        bestCost = c;
      }
    });
    this->Cheapest[u] = best;
    return best;
  }

  /// Offers u's cheapest edge as its tree's (compare-and-swap under the strict edge order).
  void offerToTree(Index u)
  {
    const auto beforeCheapest = [&](Index a, Index b) {
      const Index ea = this->Cheapest[a], eb = this->Cheapest[b];
      return this->Order.before(this->EdgeCost(a, ea), a, ea, this->EdgeCost(b, eb), b, eb);
    };
    std::atomic<Index>& f = this->From[this->Forest.tree[u]];
    Index held = f.load(std::memory_order_acquire);
    while ((held == kNone || beforeCheapest(u, held)) &&
      !f.compare_exchange_weak(held, u, std::memory_order_acq_rel, std::memory_order_acquire))
    {
    }
  }

  const IncidentEdges<Index>& Edges;
  const EdgeOrder& Order;
  const Cost& EdgeCost;
  const Differ& Differs;
  SignedForest<Index>& Forest;
  SignedUnionFind<Index> Sets;
  std::vector<unsigned char> Done;
  std::vector<Index> Cheapest;
  std::vector<std::atomic<Index>> From;
  ParallelOptions Scan;
};

/// The signed minimum spanning forest of the graph of `count` nodes, its edges in `order`. cost(a, b): an edge's cost
/// (the same both ways); differ(a, b): whether the normals of a and b disagree (the same both ways). False if aborted
/// through the progress callback.
template <typename Index, typename Cost, typename Differ>
bool signedSpanningForest(const IncidentEdges<Index>& edges, std::size_t count, const EdgeOrder& order,
  const Cost& cost, const Differ& differ, SignedForest<Index>& forest, const ParallelOptions& parallel)
{
  SignedForestRounds<Index, Cost, Differ> rounds(edges, count, order, cost, differ, forest, parallel.threads);
  for (int round = 0;; ++round)
  {
    if (parallel.progress && parallel.progress(std::min(0.9, 0.15 * round)))
    {
      return false;
    }
    rounds.findCheapestEdges();
    if (!rounds.joinTrees())
    {
      break;
    }
  }
  return true;
}

} // namespace gls
