// MLS projection onto the GLS surface (host/device): a point moves onto the algebraic sphere fitted around it, the
// sphere is refitted around the new position, and so on until the step is below a tolerance. The closed form of one
// step uses only the Pratt-normalized descriptors of the fit at the current position (docs/math.md):
// the field is s(x) = tau + g.x + kappa/2 |x|^2 with |g|^2 = 1 + 2 tau kappa, so the closest point of its zero set
// to the origin is  -2 tau / (1 + sqrt(1 + 2 tau kappa)) eta  (= -tau eta for a plane, no cancellation near kappa 0).
#pragma once

#include "gls/GridView.h"
#include "gls/Numeric.h"
#include "gls/PointScaleSpace.h"
#include "gls/ScaleSample.h"

namespace gls
{

/// Offset from the evaluation point to the closest point of the fitted sphere (length units). Requires s.valid.
GLS_INLINE Vec3 sphereProjectionOffset(const ScaleSample& s)
{
  double a = 1.0 + 2.0 * s.tau * s.kappa;
  if (a < 0.0)
  {
    a = 0.0; // |g|^2 >= 0 exactly; only rounding can make it negative
  }
  return (-2.0 * s.tau / (1.0 + squareRoot(a))) * s.eta;
}

/// Result of projecting one point.
struct ProjectionResult
{
  Vec3 position{};   ///< the projected position (the input position when !valid)
  Vec3 normal{};     ///< eta of the last fit: the unit normal of the surface there (NaN when !valid)
  int iterations = 0; ///< fits made
  bool converged = false; ///< the last step was at most tolerance * t
  bool valid = false;     ///< false when a fit along the way was undefined (too few neighbours, degenerate)
};

/// Projects p onto the MLS surface of the grid's points at scale t: at most maxIterations fits; stops when a step is
/// at most tolerance * t (then converged). The first undefined fit stops it with valid = false, position = p.
GLS_INLINE ProjectionResult projectOntoSurface(
  const GridView& g, const Vec3& p, double t, double minNeighbors, int maxIterations, double tolerance)
{
  ProjectionResult r;
  r.position = p;
  const double nan = quietNaN<double>();
  r.normal = { nan, nan, nan };
  Vec3 x = p;
  for (int it = 0; it < maxIterations; ++it)
  {
    const ScaleSample s = evaluateOneScale(g, x, t, minNeighbors);
    r.iterations = it + 1;
    if (!s.valid)
    {
      return r;
    }
    const Vec3 step = sphereProjectionOffset(s);
    x = x + step;
    r.normal = s.eta;
    if (squaredNorm(step) <= tolerance * tolerance * t * t)
    {
      r.converged = true;
      break;
    }
  }
  r.position = x;
  r.valid = true;
  return r;
}

} // namespace gls
