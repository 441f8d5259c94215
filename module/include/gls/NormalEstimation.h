// PCA normal estimation with orientation (the first step of every GLS pipeline).
// The normal of a point is the eigenvector of the smallest eigenvalue of the covariance of its neighbourhood
// (k nearest points including itself, or every point strictly inside a radius), computed in local coordinates.
// Degenerate neighbourhoods: the spread of a neighbourhood is its middle covariance eigenvalue over the largest (0 on a
// line, 1 when isotropic in the tangent plane). Below minimumSpread (a scan line, a latitude ring near a pole, three
// points along a meridian) it does not define a normal: the neighbourhood grows (twice the neighbours, or sqrt(2)
// times the radius, per step) up to maximumGrowth times the neighbours; where none reaches the spread, and where a
// point has fewer than 3 neighbours or a non-finite position, the normal is NaN (documented, never a silent value).
// 2D input (every finite point in one plane z = const) whose neighbourhoods are mostly lines (median ratio of the
// 2D covariance eigenvalues below 0.05) is a 2D curve: its normals are the in-plane perpendiculars (z component 0),
// not grown; a planar patch keeps the plane's normal.
#pragma once

#include "gls/ParallelFor.h"
#include "gls/Vec3.h"

#include <cstddef>
#include <functional>
#include <vector>

namespace gls
{

enum class NeighborhoodType
{
  KNearest = 0,  ///< the k nearest points (including the point itself)
  Radius = 1     ///< every point at distance < radius (including the point itself)
};

enum class NormalOrientation
{
  None = 0,                ///< the eigen solver's sign (deterministic, not consistent)
  TowardsPoint = 1,        ///< n . (viewpoint - p) >= 0
  AwayFromPoint = 2,       ///< n . (p - viewpoint) >= 0
  MinimumSpanningTree = 3, ///< Hoppe 1992: propagate along the MST of the k-NN graph with cost 1 - |n_i . n_j|
                           ///< (edges of equal cost ordered by their ends' point indices, so the tree is unique);
                           ///< each connected component starts from its point farthest from its centroid, oriented
                           ///< away from that centroid (outward on closed shapes); then, on a terrain-like cloud,
                           ///< the components facing down are turned up (kTerrainCoherence)
  AgreeWithReference = 4,  ///< n . reference >= 0 where the reference normal is finite and non-zero
  Up = 5,                  ///< n . up >= 0 at every point (aerial scans: PDAL's always_up, CloudCompare's +Z)
  UpAlongSpanningTree = 6, ///< airborne lidar: every normal within acos(kUpAnchorCosine) of the up direction faces up,
                           ///< point by point (ground, roofs, terrain); the others (walls, steep slopes, the sides of
                           ///< trees) agree with their neighbours along the minimum spanning tree, each component
                           ///< turned so that its upward normals, weighted by n . up, face up (a building's walls
                           ///< then face out, away from it, as its roof and the ground around it do)
  GroundUpAlongSpanningTree = 7 ///< terrestrial lidar (a scanner standing on the ground or a floor): the minimum
                           ///< spanning tree, each component turned so that its ground faces up: the lowest
                           ///< near-horizontal normals (|n . up| >= kGroundCosine) of each column of a grid over the
                           ///< cloud (kGroundColumns a side), weighted by n . up. The rest follows the tree: a room's
                           ///< ceiling faces down into the room, its walls in; a building's walls face out
};

/// Whether an orientation propagates along the minimum spanning tree (its graph and forest are made).
constexpr bool orientsAlongSpanningTree(NormalOrientation o)
{
  return o == NormalOrientation::MinimumSpanningTree || o == NormalOrientation::UpAlongSpanningTree ||
    o == NormalOrientation::GroundUpAlongSpanningTree;
}

/// GroundUpAlongSpanningTree: the columns of the grid over the cloud's horizontal extent (this many along its longer
/// side), the normals within acos(kGroundCosine) of up that count as ground or floor, and how far above its column's
/// lowest such point one still counts (this fraction of a column's side: a floor's noise and slope within it).
constexpr int kGroundColumns = 64;
constexpr double kGroundCosine = 0.9;
constexpr double kGroundLayer = 0.25;

/// UpAlongSpanningTree: the normals with |n . up| at least this (within 72.5 degrees of vertical: ground, roofs,
/// slopes up to 72 degrees) face up one by one; the steeper ones (walls, within 17.5 degrees of horizontal, where a
/// noisy normal's side is a coin toss) follow the tree.
constexpr double kUpAnchorCosine = 0.3;

/// Terrain for the minimum spanning tree orientation: a flat cloud (kTerrainFlatness) whose oriented components have
/// normals with a mean z of at least this size (each component's sum taken with its own sign); of them the components
/// whose mean z is below minus this are turned over to face +z. Terrain and roofs of pitch up to 45 degrees have means
/// of 0.7 to 1; a closed surface's normals sum to about zero, but its pieces' do not where the graph cuts it (a UV
/// sphere whose equator has no normal: two domes of means +-0.87), hence the shape's test too.
constexpr double kTerrainCoherence = 0.7;

/// The height (z extent) of a terrain-like cloud at most this times its smaller horizontal extent: an aerial tile
/// (1 km wide, 100 m of relief: 0.1) is; a closed object seen whole (a sphere: 1) is not.
constexpr double kTerrainFlatness = 0.5;

struct NormalEstimationSettings
{
  NeighborhoodType neighborhood = NeighborhoodType::KNearest;
  int k = 16;                       ///< neighbours for KNearest (at least 3)
  double radius = 0.0;              ///< length for Radius
  NormalOrientation orientation = NormalOrientation::MinimumSpanningTree;
  Vec3 viewpoint{ 0.0, 0.0, 0.0 };  ///< for TowardsPoint / AwayFromPoint
  Vec3 up{ 0.0, 0.0, 1.0 };         ///< for Up and UpAlongSpanningTree (any length but 0)
  const double* reference = nullptr; ///< 3 n reference normals for AgreeWithReference
  int graphNeighbors = 10;          ///< k of the k-NN graph used by MinimumSpanningTree
  double minimumSpread = 0.05;      ///< a neighbourhood with a smaller spread is degenerate (0: only lines)
  double maximumGrowth = 8.0;       ///< largest factor on the neighbour count when growing (1: no growth)
  ParallelOptions parallel;
  /// Whether the result holds the reach of each neighbourhood (what the GLS refinement's scales follow) and each
  /// point's degree in the tree's graph (what an orientation across pieces joins): those not wanted are left empty,
  /// and are not kept in the grid's order either (8 and 4 bytes a point less at the orientation's peak).
  bool reachWanted = true;
  bool graphDegreeWanted = true;
  /// Called, when given, once estimateNormals has read the points for the last time (its grid holds a sorted copy),
  /// so that a caller can free them before the neighbourhoods and the orientation's graph are made.
  std::function<void()> pointsCopied;
};

struct NormalEstimationResult
{
  std::vector<double> normals;      ///< 3 n components; NaN where undefined
  std::vector<int> neighborCounts;  ///< neighbours used per point (those of the last neighbourhood tried)
  std::vector<double> spread;       ///< per point: the spread of that neighbourhood (NaN with < 3 neighbours)
  std::vector<double> reach;        ///< per point: the distance to its farthest neighbour used (length); empty
                                    ///< unless reachWanted
  std::vector<int> graphDegree;     ///< per point: k of its node in the tree's graph (graphNeighbors x growth);
                                    ///< empty unless graphDegreeWanted
  std::size_t components = 0;       ///< the spanning-tree orientations: connected components oriented
};

/// Estimates (and orients) the normals of n interleaved points. Returns false if aborted through the progress
/// callback (the result is then incomplete and must not be used).
bool estimateNormals(const double* xyz, std::size_t n, const NormalEstimationSettings& settings,
  NormalEstimationResult& result);

/// GLS refinement of oriented normals (3 n, in place): each point's normal becomes eta of the oriented-sphere fit of
/// its neighbours' points and normals at the scale `factor` times reach[i] (the neighbourhood the PCA used), which
/// follows the curvature that a plane fit ignores. A point whose fit is undefined (fewer than 4 neighbours with
/// normals, non-finite reach) keeps its normal. Deterministic; false if aborted through the progress callback.
bool refineNormalsByGls(const double* xyz, std::size_t n, const std::vector<double>& reach, double factor,
  double* normals, const ParallelOptions& parallel);

/// The most memory (bytes) estimateNormals holds at once for n points, its result included, besides the caller's
/// points: the grid's sorted copy and cell index, the estimates in grid order and the result in input order, and for
/// MinimumSpanningTree the graph (graphNeighbors nearest others a node and their reverse edges) and the spanning
/// forest. A bound for a budget checked before any work: at 10M points of the bunny (k 16, graph 10, neither the
/// reach nor the degrees wanted, the caller's points freed through pointsCopied) the estimate peaked at 137 bytes a
/// point (164 before the eighth session's cuts), where this gives 141.
double normalEstimationBytes(std::size_t n, const NormalEstimationSettings& settings);

/// The bytes of the result of estimateNormals for n points (what it holds once the estimate is done).
double normalEstimationResultBytes(std::size_t n, const NormalEstimationSettings& settings);

/// How far the neighbourhoods of these settings can reach after growing: the k of the largest k-nearest
/// neighbourhood, and the largest radius (for the ghost band of a distributed run).
int reachableNeighbors(const NormalEstimationSettings& settings);
double reachableRadius(const NormalEstimationSettings& settings);

/// The median, over up to `samples` points taken at a regular stride (deterministic), of the distance from a point
/// to its k-th nearest point (itself included): a radius that holds about k points (the automatic Radius).
/// 0 when there are fewer than 2 finite points.
double medianKNearestDistance(const double* xyz, std::size_t n, int k, std::size_t samples);

/// The largest distance from a point with finite coordinates to its k-th nearest point (itself included): how far
/// the k-nearest neighbourhoods of these points reach. Infinity when there are fewer than k finite points, 0 when
/// there are none. A subset of a cloud over-estimates the reach of its points in the whole cloud, so a piece of a
/// distributed cloud that fetches the points within this distance of it has every k-nearest neighbourhood.
double kNearestReach(const double* xyz, std::size_t n, int k, const ParallelOptions& parallel);

/// Orients unit normals (3 n, NaN allowed) in place by MST propagation over the k-NN graph of the points (graph
/// queries on parallel.threads threads). `degrees` (n, or null) raises a point's k above graphNeighbors: the
/// estimate passes graphNeighbors times the growth of the point's neighbourhood, so that the graph of a scan reaches
/// across the lines where the neighbourhoods had to. `components` receives the number of connected components.
/// `rule` (MinimumSpanningTree, UpAlongSpanningTree or GroundUpAlongSpanningTree) turns the components, `up` (any
/// length but 0) for the last two. Returns false if the progress callback asked to abort (the normals are then partly
/// oriented and must not be used).
bool orientByMinimumSpanningTree(const double* xyz, std::size_t n, int graphNeighbors, double* normals,
  const ParallelOptions& parallel, std::size_t& components, const int* degrees = nullptr,
  NormalOrientation rule = NormalOrientation::MinimumSpanningTree, Vec3 up = { 0.0, 0.0, 1.0 });

} // namespace gls
