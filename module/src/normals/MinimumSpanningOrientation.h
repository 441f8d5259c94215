// Hoppe's orientation of unit normals (the MinimumSpanningTree and UpAlongSpanningTree modes of NormalEstimation):
// the orientation propagates along the minimum spanning tree of the points' k-nearest-neighbour graph for the cost
// 1 - |n_i . n_j|; each connected component is oriented from its point farthest from its centroid (outward), or,
// with an up direction, so that its upward normals face up (and those then face up one by one), or its ground does.
#pragma once

#include "gls/NeighborGrid.h"
#include "gls/NormalEstimation.h"
#include "gls/ParallelFor.h"
#include "gls/Vec3.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

namespace gls
{

/// What the orientation is given: the grid of the points (built over their finite positions; its cells are released
/// once the graph is built) and which of its points are the graph's nodes.
struct OrientationGraph
{
  NeighborGrid* grid = nullptr;
  std::size_t n = 0;                         ///< the original point count (ids below n)
  int graphNeighbors = 10;                   ///< k of the k-nearest-neighbour graph
  const int* sortedDegrees = nullptr;        ///< grid.count values (sorted order) raising a point's k above
                                             ///< graphNeighbors, or null
  const unsigned char* nodes = nullptr;      ///< grid.count flags (sorted order): a node of the graph; null: every point
  /// Called, when given, once every node's list of nearest others is made: sortedDegrees is not read again.
  std::function<void()> listsMade;
  /// Optional, what an earlier k-nearest query of the same grid found: graphNeighbors sorted indices per grid point,
  /// its nearest other points (nearest first, kNoNeighbor-padded). A point whose list is complete, holds nodes only
  /// and needs no more than graphNeighbors is not queried again. Empty: every node is queried.
  std::vector<std::uint32_t> nearestOthers;
  /// How the components are turned: MinimumSpanningTree (outward, then the terrain rule), UpAlongSpanningTree or
  /// GroundUpAlongSpanningTree (NormalEstimation.h), the last two with `up` (unit).
  NormalOrientation rule = NormalOrientation::MinimumSpanningTree;
  Vec3 up{ 0.0, 0.0, 1.0 };
};

/// The padding of OrientationGraph::nearestOthers.
constexpr std::uint32_t kNoNeighbor = std::numeric_limits<std::uint32_t>::max();

/// Orients the normals of the grid's points (grid.count, in its sorted order; the nodes' are finite) in place: the
/// others are left as they are. Every choice
/// (the components' roots, the order in which a component is collected, the tree's ties) is made on the points'
/// original indices, so the result does not depend on the grid's numbering. False if aborted through the progress
/// callback (the normals are then partly oriented and must not be used).
bool orientAlongSpanningTree(
  OrientationGraph& graph, Vec3* sortedNormals, const ParallelOptions& parallel, std::size_t& components);

} // namespace gls
