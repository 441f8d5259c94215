// The GLS descriptor of one point at one scale (docs/math.md): the Pratt-normalized algebraic sphere
// (tau, eta, kappa), its fitness phi, their exact derivatives in t, and the neighbour count. An undefined or
// unstable fit has every value NaN (valid = false), never a silent 0.
#pragma once

#include "gls/Vec3.h"

namespace gls
{

template <typename T>
struct ScaleSampleT
{
  T tau;       ///< signed offset from the evaluation point to the fitted surface (length)
  T kappa;     ///< signed curvature 1/radius (1/length); > 0 for a sphere with outward normals
  T phi;       ///< fitness in [0, 1]: 1 = normals agree perfectly with the sphere (dimensionless)
  T dtau;      ///< d tau / d t (dimensionless)
  T dkappa;    ///< d kappa / d t (1/length^2)
  Vec3T<T> eta;  ///< unit normal of the fitted field at the evaluation point
  Vec3T<T> deta; ///< d eta / d t (1/length)
  T neighbors; ///< number of neighbours strictly inside the ball of radius t
  bool valid;  ///< false when the fit is undefined; then every value but neighbors is NaN
};

using ScaleSample = ScaleSampleT<double>;

} // namespace gls
