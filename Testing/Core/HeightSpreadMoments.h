// The moment set of a test-only fit that needs one sum the oriented sphere does not (docs/architecture.md, "How to add
// a fit"): the sphere's nine values and z^2 (the local height squared); its fit gives the sphere's sample and the
// standard deviation of the neighbours' heights, sqrt(sum w z^2 / W - (sum w z / W)^2), at every scale. Its cells keep
// one more sum, y y_z^2. Run through every kernel by TestFitWithAnExtraSum.cpp, and through a test-only backend by
// TestBackendOfATestFit.cpp.
#pragma once

#include "TestClouds.h"

#include "gls/CellMoments.h"
#include "gls/MomentSet.h"
#include "gls/Numeric.h"
#include "gls/PointScaleSpace.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace glstest
{

/// The moment set of the test-only fit: the oriented sphere's values, then z^2, then |x|^2 (always the last value).
struct HeightSpreadMoments
{
  using Sphere = gls::OrientedSphereMoments;
  static constexpr int kHeightSquared = Sphere::kValues - 1; ///< the one new value: z^2 (length^2)
  static constexpr int kValues = Sphere::kValues + 1;
  static constexpr int kOmegaValues = 0;

  /// The sphere's sample and the heights' standard deviation (length; NaN where the fit is undefined).
  struct Sample
  {
    gls::ScaleSample sphere;
    double heightSpread;
  };

  /// The sphere's values of the point, then z^2 before |x|^2.
  GLS_INLINE static void pointValues(const gls::Vec3& x, double d2, const gls::Vec3& n, double* f)
  {
    Sphere::pointValues(x, d2, n, f);
    f[kValues - 1] = f[kHeightSquared];
    f[kHeightSquared] = x.z * x.z;
  }

  /// The move of origin (x + u): the sphere's values as the sphere moves them; sum z^2 gains 2 u_z sum z + u_z^2 W.
  GLS_INLINE static void shiftValues(const gls::Vec3& u, double uu, double* f)
  {
    double sphere[Sphere::kValues];
    for (int j = 0; j < kHeightSquared; ++j)
    {
      sphere[j] = f[j];
    }
    sphere[Sphere::kValues - 1] = f[kValues - 1];
    f[kHeightSquared] += 2.0 * u.z * f[gls::kPositionZ] + u.z * u.z * f[gls::kOne];
    Sphere::shiftValues(u, uu, sphere);
    for (int j = 0; j < kHeightSquared; ++j)
    {
      f[j] = sphere[j];
    }
    f[kValues - 1] = sphere[Sphere::kValues - 1];
  }

  /// What a pyramid cell keeps: the sphere's statistics and sum y y_z^2 (length^3), which z^2's gradient needs.
  struct Cell : gls::PyramidCell
  {
    gls::Vec3 offsetHeightSquared;
  };

  GLS_INLINE static void addPointToCell(Cell& cell, const gls::Vec3& y, const gls::Vec3& n)
  {
    Sphere::addPointToCell(cell, y, n);
    cell.offsetHeightSquared = cell.offsetHeightSquared + (y.z * y.z) * y;
  }

  /// sum y y_z^2 of a child at d gains T_k + 2 d_z C_k e_z + (sum y_z^2)_k d + m_k d_z^2 d (y = y_k + d, sum y_k = 0).
  GLS_INLINE static void addChildToCell(Cell& cell, const Cell& child, const gls::Vec3& d)
  {
    Sphere::addChildToCell(cell, child, d);
    const gls::Vec3 Cz = gls::offsetOffsetTimes(child, gls::Vec3{ 0.0, 0.0, 1.0 });
    cell.offsetHeightSquared = cell.offsetHeightSquared + child.offsetHeightSquared + (2.0 * d.z) * Cz +
      (child.offsetOffset[5] + child.count * d.z * d.z) * d;
  }

  /// The sphere's F and H, and z^2's: F = m x_z^2 + sum y_z^2, H = 2 x_z (C a)_z + a . sum y y_z^2.
  GLS_INLINE static void cellValues(const Cell& cell, const gls::Vec3& x, const gls::Vec3& a, double* F, double* H)
  {
    Sphere::cellValues(cell, x, a, F, H);
    F[kValues - 1] = F[kHeightSquared];
    H[kValues - 1] = H[kHeightSquared];
    F[kHeightSquared] = cell.count * x.z * x.z + cell.offsetOffset[5];
    H[kHeightSquared] = 2.0 * x.z * gls::offsetOffsetTimes(cell, a).z + gls::dot(a, cell.offsetHeightSquared);
  }

  /// The sphere's fit of its own values, and the spread from sum w z (the sphere's kPositionZ) and sum w z^2.
  GLS_INLINE static Sample fit(const double* v, const double* dv, double t, double neighbors, double minNeighbors)
  {
    double sphere[Sphere::kValues], sphereDerivative[Sphere::kValues];
    for (int j = 0; j < kHeightSquared; ++j)
    {
      sphere[j] = v[j];
      sphereDerivative[j] = dv[j];
    }
    sphere[Sphere::kValues - 1] = v[kValues - 1];
    sphereDerivative[Sphere::kValues - 1] = dv[kValues - 1];
    Sample s;
    s.sphere = Sphere::fit(sphere, sphereDerivative, t, neighbors, minNeighbors);
    const double W = v[gls::kOne];
    const double mean = v[gls::kPositionZ] / W;
    s.heightSpread =
      s.sphere.valid ? std::sqrt(std::max(0.0, v[kHeightSquared] / W - mean * mean)) : gls::quietNaN<double>();
    return s;
  }
};

/// The heights' standard deviation at scale t around p, summed point by point with the GLS weight.
inline double heightSpreadByHand(const Cloud& c, const gls::Vec3& p, double t)
{
  double W = 0.0, Z = 0.0, ZZ = 0.0;
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    const gls::Vec3 x = gls::Vec3{ c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2] } - p;
    const double w = gls::weightAt(gls::squaredNorm(x), t);
    W += w;
    Z += w * x.z;
    ZZ += w * x.z * x.z;
  }
  return std::sqrt(std::max(0.0, ZZ / W - (Z / W) * (Z / W)));
}

} // namespace glstest
