// The multi-resolution evaluation of one point (docs/math.md, "Multi-resolution evaluation"), host/device: a walk
// down an octree of cubic cells (a pyramid of levels, cells of level l of edge h0 2^l, each with the exact sums of
// its points up to the second order, CellMoments.h) that takes a whole cell as one sample where the cell is small
// against its distance from the evaluation point (edge <= Accuracy * distance to the cell's box), and the points
// themselves elsewhere. The evaluation point's own cell and the cells near it are therefore always read point by
// point. Built by MultiresolutionCloud; the moments and fits are the exact pass's (AggregateMoments.h,
// fitAllScalesFromBins).
#pragma once

#include "gls/AggregateMoments.h"
#include "gls/CellMoments.h"
#include "gls/Evaluation.h"
#include "gls/Numeric.h"
#include "gls/PointScaleSpace.h"

#include <cstdint>

namespace gls
{

constexpr int kMortonBits = 21;   ///< bits of a cell coordinate per axis in a 63-bit Morton key
constexpr int kMaxPyramidLevels = 21;

/// What the walk reads of a cell (32 bytes, apart from its sums, so that the walk touches few cache lines): its
/// cube and its children.
struct PyramidNode
{
  Vec3 corner;              ///< lower corner of the cube (length unit)
  std::uint32_t first, last; ///< level > 0: its children, cells [first, last); level 0: its points [first, last)
};

/// The pyramid as plain arrays (the same on the host and the device).
struct MultiresolutionView
{
  const PyramidNode* nodes = nullptr;  ///< all levels, finest first; the top level's cells are [topBegin, topEnd)
  /// The sums of the cells of levels summedLevel and above: node i's at cells[i - summedBegin]. The finer cells
  /// hold a few points each (about 1.5 and 3 on a surface): their sums are formed from their points when a walk
  /// takes them whole (cellMoments), which saves most of the pyramid's memory.
  const PyramidCell* cells = nullptr;
  std::uint64_t summedBegin = 0;       ///< index of the first node of level summedLevel
  int summedLevel = 0;
  const std::uint64_t* topKeys = nullptr; ///< Morton keys of the top level's cells, increasing
  std::uint64_t topBegin = 0, topEnd = 0;
  int topLevel = 0;                    ///< levels are 0 (finest) .. topLevel
  double levelSize[kMaxPyramidLevels + 1] = {}; ///< edge of a cell of each level
  Vec3 origin{};                       ///< lower corner of every level's cell (0, 0, 0)
  double accuracy = kDefaultAccuracy;  ///< a cell is one sample where edge <= accuracy * distance to its box
  int walkLevel = 0;                   ///< the points of one lattice cube of this level share one walk (walkRegion)
  /// The far parts of a walk (FarRule): the level of the finest far regions, how many levels of them, and where
  /// each begins, in half-diagonals of its region (0 or less: no far part).
  int farLevel = 0;
  int farLevelCount = 0;
  double linearizedDistance = 0.0;
  const Vec3* points = nullptr;        ///< the points in pyramid order (the cells' points are contiguous)
  const Vec3* normals = nullptr;       ///< their unit normals
  std::uint64_t count = 0;
};

/// Spreads the low 21 bits of v to every third bit (the Morton interleave of one axis).
GLS_INLINE std::uint64_t spreadMortonBits(std::uint64_t v)
{
  v &= 0x1fffffULL;
  v = (v | (v << 32)) & 0x1f00000000ffffULL;
  v = (v | (v << 16)) & 0x1f0000ff0000ffULL;
  v = (v | (v << 8)) & 0x100f00f00f00f00fULL;
  v = (v | (v << 4)) & 0x10c30c30c30c30c3ULL;
  v = (v | (v << 2)) & 0x1249249249249249ULL;
  return v;
}

/// The Morton key of cell coordinates (i, j, k), each in [0, 2^21).
GLS_INLINE std::uint64_t mortonKey(std::uint64_t i, std::uint64_t j, std::uint64_t k)
{
  return spreadMortonBits(i) | (spreadMortonBits(j) << 1) | (spreadMortonBits(k) << 2);
}

/// The box a walk measures its distances from: the lattice cube of level walkLevel that holds p (or p itself,
/// edge 0, outside the lattice). Every point of one cube has the same walk, so the CPU kernel walks once per cube;
/// since the cube holds p, a distance from it is at most p's own distance and the walk's rules hold for p.
struct WalkRegion
{
  Vec3 corner; ///< lower corner (length unit)
  double edge; ///< edge (length unit; 0: the region is the point `corner`)
};

/// The lattice cube of level `level` that holds p, or p itself (edge 0) outside the lattice.
GLS_INLINE WalkRegion latticeCube(const MultiresolutionView& v, const Vec3& p, int level)
{
  const double edge = v.levelSize[level];
  const double cells = static_cast<double>(std::int64_t(1) << (kMortonBits - level));
  const double cx = roundDown((p.x - v.origin.x) / edge);
  const double cy = roundDown((p.y - v.origin.y) / edge);
  const double cz = roundDown((p.z - v.origin.z) / edge);
  if (!(edge > 0.0 && cx >= 0.0 && cx < cells && cy >= 0.0 && cy < cells && cz >= 0.0 && cz < cells))
  {
    return { p, 0.0 };
  }
  return { { v.origin.x + cx * edge, v.origin.y + cy * edge, v.origin.z + cz * edge }, edge };
}

GLS_INLINE WalkRegion walkRegion(const MultiresolutionView& v, const Vec3& p)
{
  return latticeCube(v, p, v.walkLevel);
}

/// The half-diagonal of a cube of edge `edge`: sqrt(3) / 2 times it.
GLS_INLINE double halfDiagonal(double edge)
{
  return 0.8660254037844386 * edge;
}

/// Distance between the intervals [lo1, hi1] and [lo2, hi2] (0 where they overlap): the larger of the two one-sided
/// gaps, at least 0 (at most one of them is positive). Written as selects of the larger value, which compile to
/// max instructions: the walks test every cell they visit, on either side of p's region at random, and a branch
/// per test mispredicted about half the time.
GLS_INLINE double gapBetweenIntervals(double lo1, double hi1, double lo2, double hi2)
{
  const double after = lo2 - hi1, before = lo1 - hi2;
  const double gap = after > before ? after : before;
  return gap > 0.0 ? gap : 0.0;
}

/// Squared distance from the region to the cube [corner, corner + edge]^3 (0 where they overlap): at most the
/// squared distance from any point of the region.
GLS_INLINE double squaredDistanceToCube(const WalkRegion& a, const Vec3& corner, double edge)
{
  const double dx = gapBetweenIntervals(a.corner.x, a.corner.x + a.edge, corner.x, corner.x + edge);
  const double dy = gapBetweenIntervals(a.corner.y, a.corner.y + a.edge, corner.y, corner.y + edge);
  const double dz = gapBetweenIntervals(a.corner.z, a.corner.z + a.edge, corner.z, corner.z + edge);
  return dx * dx + dy * dy + dz * dz;
}

/// Squared distance from the region to the farthest point of the cube [corner, corner + edge]^3: per axis, how far
/// the cube reaches past the region's interval.
GLS_INLINE double squaredDistanceToFarthestCorner(const WalkRegion& a, const Vec3& corner, double edge)
{
  const auto reach = [](double lo, double hi, double alo, double ahi) {
    const double below = alo - lo, above = hi - ahi;
    const double r = below > above ? below : above;
    return r > 0.0 ? r : 0.0;
  };
  const double dx = reach(corner.x, corner.x + edge, a.corner.x, a.corner.x + a.edge);
  const double dy = reach(corner.y, corner.y + edge, a.corner.y, a.corner.y + a.edge);
  const double dz = reach(corner.z, corner.z + edge, a.corner.z, a.corner.z + a.edge);
  return dx * dx + dy * dy + dz * dz;
}

/// Cell coordinate of v along one axis at a level of edge `edge`, clamped to [0, cells - 1].
GLS_INLINE std::int64_t pyramidCoordinate(double v, double origin, double edge, std::int64_t cells)
{
  const double c = (v - origin) / edge;
  if (!(c >= 0.0))
  {
    return 0;
  }
  if (c >= static_cast<double>(cells - 1))
  {
    return cells - 1;
  }
  return static_cast<std::int64_t>(c);
}

/// Index of the top-level cell with Morton key `key` (binary search), or -1.
GLS_INLINE std::int64_t findTopCell(const MultiresolutionView& v, std::uint64_t key)
{
  std::uint64_t lo = 0, hi = v.topEnd - v.topBegin;
  while (lo < hi)
  {
    const std::uint64_t mid = (lo + hi) / 2;
    if (v.topKeys[mid] < key)
    {
      lo = mid + 1;
    }
    else
    {
      hi = mid;
    }
  }
  return lo < v.topEnd - v.topBegin && v.topKeys[lo] == key ? static_cast<std::int64_t>(v.topBegin + lo) : -1;
}

constexpr int kMaxTopCells = 27;
constexpr int kPyramidStack = kMaxTopCells + 8 * (kMaxPyramidLevels + 4);

/// Calls f(index) for each top-level cell that the region grown by r overlaps, z then y then x increasing. The
/// top cells' edge is at least the ball's diameter (or there are two per axis): at most 8 calls for a point, 27
/// for a cube.
template <typename F>
GLS_INLINE void forEachTopCell(const MultiresolutionView& v, const WalkRegion& a, double r, F&& f)
{
  const double H = v.levelSize[v.topLevel];
  const std::int64_t cells = std::int64_t(1) << (kMortonBits - v.topLevel);
  const std::int64_t x0 = pyramidCoordinate(a.corner.x - r, v.origin.x, H, cells);
  const std::int64_t x1 = pyramidCoordinate(a.corner.x + a.edge + r, v.origin.x, H, cells);
  const std::int64_t y0 = pyramidCoordinate(a.corner.y - r, v.origin.y, H, cells);
  const std::int64_t y1 = pyramidCoordinate(a.corner.y + a.edge + r, v.origin.y, H, cells);
  const std::int64_t z0 = pyramidCoordinate(a.corner.z - r, v.origin.z, H, cells);
  const std::int64_t z1 = pyramidCoordinate(a.corner.z + a.edge + r, v.origin.z, H, cells);
  for (std::int64_t z = z0; z <= z1; ++z)
  {
    for (std::int64_t y = y0; y <= y1; ++y)
    {
      for (std::int64_t x = x0; x <= x1; ++x)
      {
        const std::int64_t c = findTopCell(v,
          mortonKey(static_cast<std::uint64_t>(x), static_cast<std::uint64_t>(y), static_cast<std::uint64_t>(z)));
        if (c >= 0)
        {
          f(static_cast<std::uint32_t>(c));
        }
      }
    }
  }
}

/// Within the smallest scale, cells are held to this share of epsilon (times the smallest scale): they enter every
/// ball, the smallest ones among few other samples. The lattice is scaled so that the near cells are 0.8 to 1 times
/// this limit (nearCellEdge in MultiresolutionCloud.h). Measured (docs/performance.md, "The lattice scaled with the
/// smallest scale"; epsilon 0.5, 1M points, rocker arm / bunny): near cells of 0.314 / 0.305 of the smallest scale
/// give nu p99 0.087 / 0.079 and a 10M core (with its build) 1.29x / 1.13x faster than the 0.21 / 0.24 of the
/// earlier power-of-two lattice with a share of 0.8 (nu p99 0.074 / 0.066); on the rocker arm, near cells of 0.28 and
/// 0.36 of it (a scratch build scaling the lattice freely) gave nu p99 0.076 and 0.091.
constexpr double kNearAccuracyShare = 0.64;

/// The squared edge a cell nearer than the smallest scale may have (takenWhole): (kNearAccuracyShare epsilon times the
/// smallest scale)^2, from eps2 = epsilon^2 and floor2 = the smallest scale squared. The pyramid's levels are scaled
/// from it (nearCellEdge in MultiresolutionCloud.h), with this arithmetic, so that one level meets it exactly.
GLS_INLINE double squaredNearCellLimit(double eps2, double floor2)
{
  constexpr double nearShare2 = kNearAccuracyShare * kNearAccuracyShare;
  return eps2 * (nearShare2 * floor2);
}

/// The rule of both walks: a cell of squared edge edge2, at squared distance box2 from p's region, is taken whole
/// when its edge is at most epsilon times its distance, or, nearer than the smallest scale, kNearAccuracyShare
/// epsilon times the smallest scale (eps2 = epsilon^2, floor2 = the smallest scale squared: such a cell contributes
/// to no smaller ball, so its edge against every scale stays below epsilon), and p is at least one edge away from it
/// (p's nearest neighbours enter point by point).
GLS_INLINE bool takenWhole(double edge2, double box2, double eps2, double floor2)
{
  return edge2 <= box2 && edge2 <= (box2 > floor2 ? eps2 * box2 : squaredNearCellLimit(eps2, floor2));
}

/// The points [first, last) of the cell `node` of level `level` (a cell's points are contiguous).
GLS_INLINE void pointRange(const PyramidNode* nodes, std::uint32_t node, int level, std::uint32_t& first,
  std::uint32_t& last)
{
  std::uint32_t a = node, z = node;
  for (int l = level; l > 0; --l)
  {
    a = nodes[a].first;
    z = nodes[z].last - 1;
  }
  first = nodes[a].first;
  last = nodes[z].last;
}

/// A cell taken whole (takenWhole) below the pyramid's summed levels (whose sums a walk forms from its points) that
/// holds fewer points than this is read point by point instead: its points enter exactly, and one to three points
/// cost less to bin one by one than a cell's sample, whose spread meets 2.1 shells on average, each adding the
/// cell's F and H (docs/performance.md, "The CPU kernel": a quarter of the cells taken whole at 1M points held three
/// points or fewer, four fifths of them below the summed levels).
constexpr std::uint32_t kFewestPointsOfACellSample = 4;

/// Where the walks (forEachMultiresolutionSample, and the CPU kernel's level by level) find the points [first,
/// last) of a cell taken whole: true when it is below the summed levels and holds too few points for a cell sample
/// (kFewestPointsOfACellSample). The summed levels are left as they are: finding a cell's points there descends the
/// pyramid, which cost more than it saved at 10M points.
GLS_INLINE bool readPointByPoint(const MultiresolutionView& v, std::uint32_t node, int level, std::uint32_t& first,
  std::uint32_t& last)
{
  if (level >= v.summedLevel)
  {
    return false;
  }
  pointRange(v.nodes, node, level, first, last);
  return last - first < kFewestPointsOfACellSample;
}

/// The sums of the cell `node` of level `level`: stored, or formed from its points (momentsOfPoints about its
/// corner, as the build forms those of level summedLevel).
GLS_INLINE void cellMoments(const MultiresolutionView& v, std::uint32_t node, int level, PyramidCell& cell)
{
  if (level >= v.summedLevel)
  {
    cell = v.cells[node - v.summedBegin];
    return;
  }
  std::uint32_t first = 0, last = 0;
  pointRange(v.nodes, node, level, first, last);
  momentsOfPoints(v.points, v.normals, first, last, v.nodes[node].corner, cell);
}

/// The point a walk region's samples take their direction from (CellSample::gradient): its centre.
GLS_INLINE Vec3 regionCentre(const WalkRegion& a)
{
  const double h = 0.5 * a.edge;
  return { a.corner.x + h, a.corner.y + h, a.corner.z + h };
}

/// Where each far part of a walk begins, in half-diagonals of its far region (FarRule; docs/math.md, "Linearized
/// far cells"): a far cell's shares are expanded to the second order in the move of p within its far region, so the
/// error is of the third order in (half-diagonal / distance). Measured against the exact pass at 1M and 10M points
/// (docs/performance.md, "Linearized far cells").
constexpr double kLinearizedDistance = 10.0;

/// At most this many levels of far regions (of edges 2, 4, ... times the walk region's, each part beginning where
/// the previous one's reach doubles). One: measured at 10M points (bunny, 2 threads), three levels took 91.7 s
/// against 84.3 s for one (a walk per level and region, and three expansions added per point, cost more than the
/// larger sharing of the outer cells saved).
constexpr int kMaxFarLevels = 1;

/// The far parts of the walk of p: for each level i < count, the far region F_i (the lattice cube of level farLevel
/// + i holding p; F_0 has twice the edge of p's walk region, or is that region where it has kFarRegionLevel's edge) and
/// its reach (linearizedDistance half-diagonals of F_i, doubling with i).
/// A cell whose cube reaches at least reach_i from F_i (farthest corner), for the largest such i, belongs to far part
/// i: it is decided from F_i instead of p's walk region (taken whole or opened by its distance from F_i, never read
/// point by point), so that every point of F_i finds the same such cells; those entirely beyond reach_i from F_i are
/// F_i's linearized cells, whose shares are expanded at F_i's centre and moved to p to the second order
/// (movedShare). Inactive (count 0) where the regions have no extent.
struct FarRule
{
  WalkRegion region[kMaxFarLevels];
  double reach2[kMaxFarLevels]; ///< reach squared
  int count = 0;
};

GLS_INLINE FarRule farRule(const MultiresolutionView& v, const Vec3& p)
{
  FarRule f;
  const int count = v.linearizedDistance > 0.0 ? v.farLevelCount : 0;
  for (int i = 0; i < count && i < kMaxFarLevels; ++i)
  {
    f.region[i] = latticeCube(v, p, v.farLevel + i);
    const double reach = v.linearizedDistance * halfDiagonal(f.region[i].edge);
    f.reach2[i] = reach * reach;
    f.count = f.region[i].edge > 0.0 ? i + 1 : 0;
    if (f.count == 0)
    {
      break;
    }
  }
  return f;
}

/// How a walk treats a cell of cube [corner, corner + edge]^3: it is decided from far region F_{far - 1} (0: from p's
/// walk region), box2 its distance from there; if taken whole, it is a linearized cell of far part `linearized` - 1,
/// the largest j <= far - 1 whose region it lies entirely beyond reach_j of (0: a near sample). Both depend only on
/// F_j and the larger regions, so every point of F_j finds the same linearized cells of part j.
struct CellPlace
{
  int far, linearized;
  double box2;
};

GLS_INLINE CellPlace placeCell(const FarRule& f, const WalkRegion& region, const Vec3& corner, double edge)
{
  // Both tests hold for a prefix of the far parts (a larger region is nearer and its reach twice as long), so each
  // stops at its first failure, and a near cell costs one test.
  int far = 0;
  while (far < f.count && squaredDistanceToFarthestCorner(f.region[far], corner, edge) >= f.reach2[far])
  {
    ++far;
  }
  if (far == 0)
  {
    return { 0, 0, squaredDistanceToCube(region, corner, edge) };
  }
  CellPlace c{ far, 0, squaredDistanceToCube(f.region[far - 1], corner, edge) };
  while (c.linearized < far &&
    (c.linearized == far - 1 ? c.box2 : squaredDistanceToCube(f.region[c.linearized], corner, edge)) >=
      f.reach2[c.linearized])
  {
    ++c.linearized;
  }
  return c;
}

/// Whether a cell of far region F (FarRule) taken whole is linearized: only where its spread of squared distances,
/// seen from F's centre (half-width `half`, direction `a` = its centroid - the centre), is at least as wide as its
/// mean's move across F (|delta| = ||u|^2 - 2 a . u| <= 2 |a| h + h^2 for |u| <= h, F's half-diagonal). A narrower
/// spread can cross a scale's sphere as p moves within F, its share jumping from one shell to the next (a narrow one
/// goes whole to the shell of its mean), which no expansion at the centre follows: such a cell is sampled for each
/// point instead, as a near cell (measured: a wall of the rocker arm facing p, 5,500 of 28,000 points in the wrong
/// ball, nu 800 times off at 3M points; docs/performance.md, "Linearized far cells").
GLS_INLINE bool linearizable(double half, const Vec3& a, const WalkRegion& F)
{
  const double h = halfDiagonal(F.edge);
  return half >= h * (2.0 * squareRoot(squaredNorm(a)) + h);
}

/// The region a walk's top cells are found from: the largest far region, or p's walk region.
GLS_INLINE const WalkRegion& outermostRegion(const FarRule& f, const WalkRegion& region)
{
  return f.count > 0 ? f.region[f.count - 1] : region;
}

/// Calls sample(node, level, farPart) for every cell taken whole (takenWhole, with `smallest` the smallest scale;
/// not readPointByPoint) and point(i) for every point read one by one, for the ball of radius r around p: every point
/// of the ball is in exactly one of them (points of a cell taken whole may lie outside the ball; the caller bins them
/// by its CellSample's spread). Distances are measured from p's walkRegion, or, for the cells of a far part
/// (FarRule, placeCell), from its far region, so the samples and their order are fixed by the pyramid and those
/// regions alone; farPart is i + 1 for a linearized cell of far part i, else 0.
template <typename CellVisit, typename PointVisit>
GLS_INLINE void forEachMultiresolutionSample(const MultiresolutionView& v, const Vec3& p, double r, double smallest,
  CellVisit&& sample, PointVisit&& point)
{
  const double floor2 = smallest * smallest;
  if (v.topEnd <= v.topBegin || !(r > 0.0))
  {
    return;
  }
  const double r2 = r * r;
  const double eps2 = v.accuracy * v.accuracy;
  std::uint32_t stack[kPyramidStack];
  int stackLevel[kPyramidStack];
  int top = 0;
  // The top-level cells the balls of p's far region overlap (it holds p's walk region), pushed last to first so that
  // they are visited in order.
  const WalkRegion region = walkRegion(v, p);
  const FarRule far = farRule(v, p);
  std::uint32_t tops[kMaxTopCells];
  int found = 0;
  forEachTopCell(v, outermostRegion(far, region), r, [&](std::uint32_t c) {
    if (found < kMaxTopCells)
    {
      tops[found++] = c;
    }
  });
  for (int i = found - 1; i >= 0; --i)
  {
    stack[top] = tops[i];
    stackLevel[top] = v.topLevel;
    ++top;
  }
  while (top > 0)
  {
    --top;
    const PyramidNode& cell = v.nodes[stack[top]];
    const int level = stackLevel[top];
    const double edge = v.levelSize[level];
    const CellPlace place = placeCell(far, region, cell.corner, edge);
    if (!(place.box2 < r2))
    {
      continue;
    }
    // A cell taken whole enters as its sample, or point by point where it holds too few points (not in the far
    // part); a level-0 cell not taken whole is read point by point.
    const bool whole = takenWhole(edge * edge, place.box2, eps2, floor2);
    std::uint32_t first = cell.first, last = cell.last;
    if (whole && (place.far > 0 || !readPointByPoint(v, stack[top], level, first, last)))
    {
      sample(stack[top], level, place.linearized);
    }
    else if (whole || level == 0)
    {
      for (std::uint32_t i = first; i < last; ++i)
      {
        point(i);
      }
    }
    else
    {
      // Children pushed last to first, so that they are visited in pyramid order.
      for (std::uint32_t c = cell.last; c > cell.first && top < kPyramidStack; --c)
      {
        stack[top] = c - 1;
        stackLevel[top] = level - 1;
        ++top;
      }
    }
  }
}

/// The terms of the ball of the largest scale around p, each with its bin k: cellShare(k, sample, share) for each
/// shell a cell taken whole meets (its CellSample: its points weighted by a linear field, their squared distances
/// spread over the shells; a linearized cell's shares formed at its far region's centre and moved to p, movedShare),
/// point(k, x, d2, normal) for each point read one by one inside the ball (x = its position - p, d2 = |x|^2). The
/// walk (forEachMultiresolutionSample) fixes the terms and their order.
template <typename CellShare, typename PointTerm>
GLS_INLINE void forEachMultiresolutionTerm(
  const MultiresolutionView& v, const Vec3& p, const ScaleBinning& b, CellShare&& cellShare, PointTerm&& point)
{
  const double r = b.scales[b.count - 1];
  const double r2 = r * r;
  const Vec3 anchor = regionCentre(walkRegion(v, p));
  const FarRule far = farRule(v, p);
  forEachMultiresolutionSample(
    v, p, r, b.scales[0],
    [&](std::uint32_t node, int level, int farPart) {
      PyramidCell cell;
      cellMoments(v, node, level, cell);
      CellSample s;
      // A far cell too narrow to linearize is sampled as a near cell (direction from the walk region's centre).
      const Vec3 centre = farPart > 0 ? regionCentre(far.region[farPart - 1]) : anchor;
      const bool linearized = farPart > 0 &&
        linearizable(spreadHalfWidth(cell, cell.centroid - centre), cell.centroid - centre, far.region[farPart - 1]);
      const Vec3 a = cell.centroid - (linearized ? centre : anchor);
      makeCellSample(cell, p, a, s);
      const double mean = squaredNorm(cell.centroid - p) + s.spreadPerPoint;
      if (!linearized)
      {
        forEachShellOfSpread(b, r2, mean, s.halfWidth, [&](int k, const ShellShare& share) { cellShare(k, s, share); });
        return;
      }
      // A linearized cell: its shares expanded at the far region's centre, moved to p's mean. With u = p - centre,
      // the mean moves by delta = |u|^2 - 2 a . u; the second-order term keeps (2 a . u)^2 / 2 of delta^2 / 2.
      const double centreMean = squaredNorm(a) + s.spreadPerPoint;
      const double delta = mean - centreMean;
      const double au = dot(a, p - centre);
      forEachShellOfSpreadExpanded(b, r2, centreMean, s.halfWidth, [&](int k, const ShellShareExpansion& e) {
        cellShare(k, s, movedShare(e, delta, 2.0 * au * au));
      });
    },
    [&](std::uint32_t i) {
      const Vec3 x = v.points[i] - p;
      const double d2 = squaredNorm(x);
      if (d2 < r2)
      {
        point(firstScaleHolding(b, d2), x, d2, v.normals[i]);
      }
    });
}

/// Fits every scale of the evaluation point p from the multi-resolution samples of the ball of the largest scale
/// (forEachMultiresolutionTerm): points inside the ball enter exactly, as in evaluateAllScales; a cell taken whole
/// enters as its CellSample. b: the S increasing scales and their binning table; bins: S scratch moment sets; out: S
/// samples.
GLS_INLINE void evaluateAllScalesMultiresolution(const MultiresolutionView& v, const Vec3& p, const ScaleBinning& b,
  double minNeighbors, AggregateMoments* bins, ScaleSample* out)
{
  if (b.count <= 0)
  {
    return;
  }
  for (int k = 0; k < b.count; ++k)
  {
    clearMoments(bins[k]);
  }
  forEachMultiresolutionTerm(
    v, p, b, [&](int k, const CellSample& s, const ShellShare& share) { addCellShare(bins[k], s, share); },
    [&](int k, const Vec3& x, double d2, const Vec3& n) { addPoint(bins[k], x, d2, n); });
  fitAllScalesFromBins(b, minNeighbors, bins, out);
}

/// evaluateAllScalesMultiresolution, bit for bit, with the scales taken G at a time (fitAllScalesByWindows): the
/// walk of the largest ball is repeated per window (the same terms in the same order), and only the window's bins
/// are added to. No scratch bins: the CUDA kernel's loop, where S bins per thread in memory are read and written
/// scattered.
template <int G>
GLS_INLINE void evaluateAllScalesMultiresolutionByWindows(const MultiresolutionView& v, const Vec3& p,
  const ScaleBinning& b, double minNeighbors, ScaleSample* out)
{
  if (b.count <= 0)
  {
    return;
  }
  fitAllScalesByWindows<G, AggregateMoments>(b, minNeighbors,
    [&](int k0, int, AggregateMoments* window) {
      forEachMultiresolutionTerm(
        v, p, b,
        [&](int k, const CellSample& s, const ShellShare& share) {
          addToWindowSlot<G>(window, k - k0, [&](AggregateMoments& m) { addCellShare(m, s, share); });
        },
        [&](int k, const Vec3& x, double d2, const Vec3& n) {
          addToWindowSlot<G>(window, k - k0, [&](AggregateMoments& m) { addPoint(m, x, d2, n); });
        });
    },
    out);
}

} // namespace gls
