// The far parts of a multi-resolution walk (docs/math.md, "Linearized far cells"), host/device: beyond a distance of
// some half-diagonals of a far region, a cell's shares are expanded once per region to the second order in the move
// of the evaluation point within it (FarRule, placeCell).
#pragma once

#include "gls/MultiresolutionView.h"

namespace gls
{

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

} // namespace gls
