#include "gls/DirectionStability.h"

#include <algorithm>
#include <cmath>

namespace gls
{
namespace
{

/// Whether a scale's directions count: defined, and the curvatures apart by the significance.
bool anisotropic(const PrincipalCurvatures& c, double significance)
{
  const double largest = std::max(std::abs(c.k1), std::abs(c.k2));
  return std::isfinite(c.d1.x) && std::isfinite(c.k1) && std::isfinite(c.k2) && largest > 0.0 &&
    c.k1 - c.k2 >= significance * largest;
}

double anisotropyOf(const PrincipalCurvatures& c)
{
  return (c.k1 - c.k2) / (std::abs(c.k1) + std::abs(c.k2));
}

} // namespace

StableDirection steadiestDirection(const PrincipalCurvatures* c, const double* scales, int S, double significance)
{
  const double nan = std::nan("");
  StableDirection best{ nan, nan, nan, nan, { nan, nan, nan }, nan };
  for (int k = 0; k + 1 < S; ++k)
  {
    const PrincipalCurvatures &a = c[k], &b = c[k + 1];
    if (!anisotropic(a, significance) || !anisotropic(b, significance))
    {
      continue;
    }
    // The angle between the lines, from its sine and cosine (well conditioned where it is small, unlike acos).
    const double angle = std::atan2(std::sqrt(squaredNorm(cross(a.d1, b.d1))), std::abs(dot(a.d1, b.d1)));
    const double rate = angle / std::log(scales[k + 1] / scales[k]);
    if (!(rate < best.turnRate) && !std::isnan(best.turnRate))
    {
      continue;
    }
    best.scale = std::sqrt(scales[k] * scales[k + 1]);
    best.turnRate = rate;
    best.anisotropy = 0.5 * (anisotropyOf(a) + anisotropyOf(b));
    best.shapeIndex = 0.5 * (shapeIndex(a, scales[k]) + shapeIndex(b, scales[k + 1]));
    best.direction = canonicalDirection(a.d1 + (dot(a.d1, b.d1) < 0.0 ? -1.0 : 1.0) * b.d1);
    const double si = best.shapeIndex;
    best.ridgeValley = si >= kRidgeShapeIndexLow && si <= kRidgeShapeIndexHigh
      ? 1.0
      : (si <= -kRidgeShapeIndexLow && si >= -kRidgeShapeIndexHigh ? -1.0 : 0.0);
  }
  return best;
}

} // namespace gls
