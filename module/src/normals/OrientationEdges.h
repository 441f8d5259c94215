// The edges of the orientation's k-nearest-neighbour graph as each node sees them: the node's own list of nearest
// other nodes, and the nodes whose lists hold it while its own list does not hold them. Every undirected edge is
// thus seen from both of its ends, without a sorted symmetric adjacency.
#pragma once

#include "gls/ParallelFor.h"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <limits>
#include <vector>

namespace gls
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
    if (extraNodes.empty())
    {
      return;
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

  /// True when node s's list holds node v.
  bool holds(std::size_t s, Index v) const
  {
    bool found = false;
    this->forEach(s, [&](Index w) { found = found || w == v; });
    return found;
  }
};

/// Every edge at each node: its own nearest-other list and, in `reverse`, the nodes that list it without being in its
/// list (in no particular order: nothing that uses them depends on it).
template <typename Index>
struct IncidentEdges
{
  NearestLists<Index> lists;
  std::vector<std::size_t> reverseStart; ///< count + 1 offsets into reverse
  std::vector<Index> reverse;

  /// Calls f(v) for each node v that shares an edge with node s (once or, rarely, twice).
  template <typename F>
  void forEach(std::size_t s, F&& f) const
  {
    this->lists.forEach(s, f);
    for (std::size_t e = this->reverseStart[s]; e < this->reverseStart[s + 1]; ++e)
    {
      f(this->reverse[e]);
    }
  }

  /// Fills `reverse` from the lists of `count` nodes (in parallel). False if aborted.
  bool addReverse(std::size_t count, const ParallelOptions& parallel)
  {
    std::vector<std::atomic<Index>> filled(count); // value-initialized: zero
    ParallelOptions options;
    options.threads = parallel.threads;
    options.chunk = 4096;
    options.progress = parallel.progress;
    const auto eachOneWay = [&](auto&& add) {
      return parallelFor(count, options, [&](std::size_t begin, std::size_t end, int) {
        for (std::size_t u = begin; u < end; ++u)
        {
          this->lists.forEach(u, [&](Index v) {
            if (!this->lists.holds(v, static_cast<Index>(u)))
            {
              add(v, static_cast<Index>(u));
            }
          });
        }
      });
    };
    if (!eachOneWay([&](Index v, Index) { filled[v].fetch_add(1, std::memory_order_relaxed); }))
    {
      return false;
    }
    this->reverseStart.assign(count + 1, 0);
    for (std::size_t s = 0; s < count; ++s)
    {
      this->reverseStart[s + 1] = this->reverseStart[s] + filled[s].load(std::memory_order_relaxed);
      filled[s].store(0, std::memory_order_relaxed);
    }
    this->reverse.resize(this->reverseStart[count]);
    return eachOneWay([&](Index v, Index u) {
      this->reverse[this->reverseStart[v] + filled[v].fetch_add(1, std::memory_order_relaxed)] = u;
    });
  }
};

} // namespace gls
