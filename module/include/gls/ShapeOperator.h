// Principal curvatures and directions at every scale: the shape operator of the oriented sphere fit, how its normal
// field turns as the evaluation point moves (docs/math.md, "Principal curvatures"; after Lejemble, Coeurjolly,
// Barthe and Mellado, "Stable and efficient differential estimators on oriented point clouds", SGP 2021, whose
// algebraic shape operator this is, at every scale of one pass). Host/device.
//
// The fit at p weighs its neighbours by w(|q_i - p|^2 / t^2); moving p by e changes each weight by omega_i (x_i . e),
// omega = (4/t^2)(1 - d^2/t^2), and each local position x_i by -e. So the spatial derivatives of the sphere's sums
// need, besides them, the omega-weighted sums of x, x x^T, n x^T, (x . n) x and |x|^2 x. Of the sphere's own values
// they are (4/t^2) v + dv / t, and sum omega |x|^2 f = t sum (dw/dt) f, so |x|^2 x, the trace of x x^T and that of
// n x^T come from them; the 16 others are ShapeOperatorMoments' omega-values (MomentSet.h), of which the kernels keep
// two moments (MomentBins.h): the one pass, its windowed form and the CPU kernel run the set unchanged.
#pragma once

#include "gls/MomentSet.h"
#include "gls/Numeric.h"
#include "gls/ScaleSample.h"
#include "gls/ShapeOperatorCells.h"
#include "gls/SphereFit.h"
#include "gls/WeightedSums.h"

namespace gls
{

/// Directions are NaN where the principal curvatures differ by at most this much times 1/t (an umbilic at the
/// scale of the fit: a sphere, a plane, or a point where the two curvatures cross).
constexpr double kUmbilicTolerance = 1e-6;

/// The principal curvatures k1 >= k2 (1/length; > 0 on a sphere with outward normals, like kappa) and their unit
/// tangent directions d1, d2 (d1 x d2 = eta; d1's largest component is positive). All NaN where the fit is undefined
/// or degenerate; d1, d2 NaN at an umbilic (k1 - k2 <= kUmbilicTolerance / t).
struct PrincipalCurvatures
{
  double k1, k2;
  Vec3 d1, d2;
};

/// The sample of ShapeOperatorMoments' fit at one scale: the oriented sphere's, and the principal curvatures.
struct CurvatureSample
{
  ScaleSample sphere;
  PrincipalCurvatures principal;
};

/// The omega-weighted sums (omega = (4/t^2)(1 - d^2/t^2) in the ball) a move of the evaluation point needs: moving p
/// by e changes sum w f by sum omega (x . e) f, plus the sums' own change with x (-e).
struct SpatialSums
{
  Vec3 X;                ///< sum omega x (length / length^2)
  double XX[6];          ///< sum omega x x^T as xx, xy, xz, yy, yz, zz
  double NX[9];          ///< sum omega n x^T, [3 a + b] = n_a x_b
  Vec3 XdotNX;           ///< sum omega (x . n) x
  Vec3 SquaredX;         ///< sum omega |x|^2 x
};

GLS_INLINE PrincipalCurvatures undefinedCurvatures()
{
  const double nan = quietNaN<double>();
  return { nan, nan, { nan, nan, nan }, { nan, nan, nan } };
}

/// A unit vector orthogonal to the unit vector n: the axis least aligned with n, less its part along n.
GLS_INLINE Vec3 orthogonalUnit(const Vec3& n)
{
  const double ax = absolute(n.x), ay = absolute(n.y), az = absolute(n.z);
  const Vec3 axis =
    ax <= ay && ax <= az ? Vec3{ 1.0, 0.0, 0.0 } : (ay <= az ? Vec3{ 0.0, 1.0, 0.0 } : Vec3{ 0.0, 0.0, 1.0 });
  const Vec3 v = axis - dot(axis, n) * n;
  return (1.0 / squareRoot(squaredNorm(v))) * v;
}

/// The unit vector along the line of v (non-zero) with its largest component positive: the sign convention of
/// the principal directions, which are lines.
GLS_INLINE Vec3 canonicalDirection(const Vec3& v)
{
  const Vec3 u = (1.0 / squareRoot(squaredNorm(v))) * v;
  const double ax = absolute(u.x), ay = absolute(u.y), az = absolute(u.z);
  const double largest = ax >= ay && ax >= az ? u.x : (ay >= az ? u.y : u.z);
  return largest < 0.0 ? -1.0 * u : u;
}

/// The principal curvatures of the symmetric 2x2 shape operator [[a, b], [b, c]] in the tangent basis (b1, b2) of
/// eta, at scale t: its eigenvalues k1 >= k2 and eigenvectors.
GLS_INLINE PrincipalCurvatures principalOf(double a, double b, double c, const Vec3& b1, const Vec3& b2,
  const Vec3& eta, double t)
{
  const double mean = 0.5 * (a + c), half = 0.5 * (a - c);
  const double r = squareRoot(half * half + b * b);
  PrincipalCurvatures pc;
  pc.k1 = mean + r;
  pc.k2 = mean - r;
  const double nan = quietNaN<double>();
  if (!(pc.k1 - pc.k2 > kUmbilicTolerance / t))
  {
    pc.d1 = pc.d2 = { nan, nan, nan };
    return pc;
  }
  // (b, k1 - a) and (k1 - c, b) are both eigenvectors of k1 where non-zero: the longer, for its precision.
  const double u1 = b, v1 = pc.k1 - a, u2 = pc.k1 - c, v2 = b;
  const bool first = u1 * u1 + v1 * v1 >= u2 * u2 + v2 * v2;
  pc.d1 = canonicalDirection(first ? u1 * b1 + v1 * b2 : u2 * b1 + v2 * b2);
  pc.d2 = cross(eta, pc.d1);
  return pc;
}

/// The derivative of u_l (fitOrientedSphere's linear term) as the evaluation point moves along the unit vector e, from
/// the w-weighted sums s, the spatial sums g and the fit's uq and u_l (invW = 1 / s.W, halfInvDeno = 1 / (2 deno)).
GLS_FORCE_INLINE Vec3 linearTermDerivative(const WeightedSums& s, const SpatialSums& g, const Vec3& e, double invW,
  double halfInvDeno, double PdotN, double PdotP, double uq, const Vec3& ul)
{
  const double invW2 = invW * invW;
  const double dW = dot(g.X, e);
  const double ev[3] = { e.x, e.y, e.z };
  double XXe[3];
  symmetricTimes(g.XX, ev, XXe);
  const Vec3 dP = Vec3{ XXe[0], XXe[1], XXe[2] } - s.W * e;
  const Vec3 dN{ g.NX[0] * e.x + g.NX[1] * e.y + g.NX[2] * e.z, g.NX[3] * e.x + g.NX[4] * e.y + g.NX[5] * e.z,
    g.NX[6] * e.x + g.NX[7] * e.y + g.NX[8] * e.z };
  const double dPN = dot(g.XdotNX, e) - dot(s.N, e);
  const double dPP = dot(g.SquaredX, e) - 2.0 * dot(s.P, e);
  const double dnume = dPN - (dot(dP, s.N) + dot(s.P, dN)) * invW + PdotN * dW * invW2;
  const double ddeno = dPP - 2.0 * dot(s.P, dP) * invW + PdotP * dW * invW2;
  const double duq = (dnume - 2.0 * uq * ddeno) * halfInvDeno;
  return invW * (dN - (2.0 * duq) * s.P - (2.0 * uq) * dP - dW * ul);
}

/// The principal curvatures of the oriented sphere fitted to the sums s (w-weighted, about p) at scale t, from the
/// spatial sums g: the tangent part of D eta = (I - eta eta^T) D u_l / sqrt(phi) (D: the derivative with respect to
/// p; u_l and phi as in fitOrientedSphere, whose sample `sphere` is the fit of s), symmetrized, in a tangent basis
/// (b1, b2) of eta: D u_l along b1 and b2 only (linearTermDerivative), whose parts along eta the basis drops. On a
/// sphere D u_l = 2 u_q I, so k1 = k2 = kappa. Undefined (NaN) where the sphere is, and where its spread term
/// vanishes (its points at one place: no curvature).
GLS_FORCE_INLINE PrincipalCurvatures principalCurvaturesOf(
  const WeightedSums& s, const SpatialSums& g, const ScaleSample& sphere, double t)
{
  const double invW = 1.0 / s.W;
  const double PdotN = dot(s.P, s.N), PdotP = dot(s.P, s.P);
  const double nume = s.PN - PdotN * invW, deno = s.PP - PdotP * invW;
  const double spreadScale = s.PP > PdotP * invW ? s.PP : PdotP * invW;
  if (!sphere.valid || !(absolute(deno) > kDegenerateSpreadEpsilon * spreadScale))
  {
    return undefinedCurvatures();
  }
  const double halfInvDeno = 1.0 / (2.0 * deno);
  const double uq = nume * halfInvDeno;
  const Vec3 ul = invW * (s.N - (2.0 * uq) * s.P);
  const Vec3& eta = sphere.eta;
  const Vec3 b1 = orthogonalUnit(eta), b2 = cross(eta, b1);
  const Vec3 Sb1 = linearTermDerivative(s, g, b1, invW, halfInvDeno, PdotN, PdotP, uq, ul);
  const Vec3 Sb2 = linearTermDerivative(s, g, b2, invW, halfInvDeno, PdotN, PdotP, uq, ul);
  // The 2x2 form in (b1, b2), symmetrized, over sqrt(phi).
  const double invSqrtPhi = 1.0 / squareRoot(sphere.phi);
  const double a = dot(b1, Sb1) * invSqrtPhi, c = dot(b2, Sb2) * invSqrtPhi;
  const double b = 0.5 * (dot(b1, Sb2) + dot(b2, Sb1)) * invSqrtPhi;
  PrincipalCurvatures pc = principalOf(a, b, c, b1, b2, eta, t);
  if (!(isFinite(pc.k1) && isFinite(pc.k2)))
  {
    return undefinedCurvatures();
  }
  return pc;
}

/// The oriented sphere's moment set with the values its shape operator needs (ShapeOperatorValue): the exact
/// evaluation's kernels run it as they run the sphere's, and the multi-resolution ones with its own cells
/// (ShapeOperatorCells.h; summedCellsOf).
struct ShapeOperatorMoments
{
  using Sphere = OrientedSphereMoments;
  static constexpr int kValues = kShapeOperatorValues;
  static constexpr int kOmegaValues = kShapeOperatorSquaredPosition - kOffsetOffset; ///< 16
  using Sample = CurvatureSample;
  using Cell = CurvatureCell;

  /// The sphere's values of f (|x|^2 at its place in the sphere's set), and back.
  GLS_INLINE static void sphereValuesOf(const double* f, double* sphere)
  {
    for (int j = 0; j < kSquaredPosition; ++j)
    {
      sphere[j] = f[j];
    }
    sphere[kSquaredPosition] = f[kShapeOperatorSquaredPosition];
  }
  GLS_INLINE static void setSphereValues(const double* sphere, double* f)
  {
    for (int j = 0; j < kSquaredPosition; ++j)
    {
      f[j] = sphere[j];
    }
    f[kShapeOperatorSquaredPosition] = sphere[kSquaredPosition];
  }

  /// The move of origin (x + u): the omega-values' from the sphere's sums before they move, then the sphere's.
  GLS_FORCE_INLINE static void shiftValues(const Vec3& u, double uu, double* f)
  {
    shiftCurvatureValues(u, f);
    double sphere[Sphere::kValues];
    sphereValuesOf(f, sphere);
    Sphere::shiftValues(u, uu, sphere);
    setSphereValues(sphere, f);
  }

  /// The move of origin of the weighted sums (v weighted by w, the omega-values' by omega; dv by dw/dt, MomentBins.h):
  /// the sphere's values in both as sums of one weight each; the omega-values from the omega-weighted sums of the
  /// sphere's values about o, (4/t^2) v + dv / t (as fit forms them), before these move. The same sums as moving
  /// the moments and weighting them (the move is linear, and a point's weights are p's), in fewer operations.
  GLS_FORCE_INLINE static void shiftWeightedValues(const Vec3& u, double uu, double t, double* v, double* dv)
  {
    const double a = 4.0 / (t * t), b = 1.0 / t;
    double omegaWeighted[kValues];
    for (int j = 0; j < kSquaredPosition; ++j)
    {
      omegaWeighted[j] = a * v[j] + b * dv[j];
    }
    for (int j = kSquaredPosition; j < kValues; ++j)
    {
      omegaWeighted[j] = v[j];
    }
    shiftCurvatureValues(u, omegaWeighted);
    for (int j = kOffsetOffset; j < kShapeOperatorSquaredPosition; ++j)
    {
      v[j] = omegaWeighted[j];
    }
    double sphere[Sphere::kValues];
    sphereValuesOf(v, sphere);
    Sphere::shiftValues(u, uu, sphere);
    setSphereValues(sphere, v);
    sphereValuesOf(dv, sphere);
    Sphere::shiftValues(u, uu, sphere);
    setSphereValues(sphere, dv);
  }

  GLS_FORCE_INLINE static void addPointToCell(Cell& cell, const Vec3& y, const Vec3& n)
  {
    Sphere::addPointToCell(cell, y, n);
    addPointToCurvatureCell(cell, y, n);
  }

  GLS_INLINE static void addChildToCell(Cell& cell, const Cell& child, const Vec3& d)
  {
    Sphere::addChildToCell(cell, child, d);
    addChildToCurvatureCell(cell, child, d);
  }

  GLS_FORCE_INLINE static void cellValues(const Cell& cell, const Vec3& x, const Vec3& a, double* F, double* H)
  {
    double sphereF[Sphere::kValues], sphereH[Sphere::kValues];
    Sphere::cellValues(cell, x, a, sphereF, sphereH);
    setSphereValues(sphereF, F);
    setSphereValues(sphereH, H);
    curvatureCellValues(cell, x, a, F, H);
  }

  GLS_FORCE_INLINE static void pointValues(const Vec3& x, double d2, const Vec3& n, double* f)
  {
    Sphere::pointValues(x, d2, n, f); // its |x|^2 (at kSquaredPosition) is overwritten below, and set last
    const double xv[3] = { x.x, x.y, x.z }, nv[3] = { n.x, n.y, n.z };
    const double xx[5] = { x.x * x.x, x.x * x.y, x.x * x.z, x.y * x.y, x.y * x.z };
    for (int k = 0; k < 5; ++k)
    {
      f[kOffsetOffset + k] = xx[k];
    }
    for (int k = 0; k < 8; ++k)
    {
      f[kNormalOffset + k] = nv[k / 3] * xv[k % 3];
    }
    const double xn = f[kPositionDotNormal];
    for (int a = 0; a < 3; ++a)
    {
      f[kOffsetDotNormalOffset + a] = xn * xv[a];
    }
    f[kShapeOperatorSquaredPosition] = d2;
  }

  /// The sphere's fit, and the principal curvatures from the omega-weighted sums: the omega-values' own (v), the
  /// sphere's values' (4/t^2) v + dv / t.
  GLS_FORCE_INLINE static Sample fit(const double* v, const double* dv, double t, double neighbors, double minNeighbors)
  {
    double sv[Sphere::kValues], sdv[Sphere::kValues];
    sphereValuesOf(v, sv);
    sphereValuesOf(dv, sdv);
    Sample r;
    r.sphere = Sphere::fit(sv, sdv, t, neighbors, minNeighbors);
    if (!r.sphere.valid)
    {
      r.principal = undefinedCurvatures();
      return r;
    }
    const double a = 4.0 / (t * t), b = 1.0 / t;
    const auto omega = [&](int j) { return a * v[j] + b * dv[j]; };
    SpatialSums g;
    g.X = { omega(kPositionX), omega(kPositionY), omega(kPositionZ) };
    for (int k = 0; k < 5; ++k)
    {
      g.XX[k] = v[kOffsetOffset + k];
    }
    g.XX[5] = t * dv[kOne] - g.XX[0] - g.XX[3]; // sum omega |x|^2 = t sum (dw/dt)
    for (int k = 0; k < 8; ++k)
    {
      g.NX[k] = v[kNormalOffset + k];
    }
    g.NX[8] = omega(kPositionDotNormal) - g.NX[0] - g.NX[4]; // the trace: sum omega x . n
    const int dn = kOffsetDotNormalOffset;
    g.XdotNX = { v[dn], v[dn + 1], v[dn + 2] };
    g.SquaredX = { t * dv[kPositionX], t * dv[kPositionY], t * dv[kPositionZ] }; // sum omega |x|^2 x
    WeightedSums s, ds;
    toWeightedSums(sv, sdv, s, ds);
    r.principal = principalCurvaturesOf(s, g, r.sphere, t);
    return r;
  }
};

/// Mean curvature H = (k1 + k2) / 2 (1/length; equal to kappa on a sphere).
GLS_INLINE double meanCurvature(const PrincipalCurvatures& c)
{
  return 0.5 * (c.k1 + c.k2);
}

/// Gaussian curvature K = k1 k2 (1/length^2).
GLS_INLINE double gaussianCurvature(const PrincipalCurvatures& c)
{
  return c.k1 * c.k2;
}

/// Curvedness sqrt((k1^2 + k2^2) / 2) (1/length; 0 on a plane).
GLS_INLINE double curvedness(const PrincipalCurvatures& c)
{
  return squareRoot(0.5 * (c.k1 * c.k1 + c.k2 * c.k2));
}

/// Koenderink's shape index (2/pi) atan((k1 + k2) / (k1 - k2)) in [-1, 1] (dimensionless) at scale t: +1 a dome (a
/// sphere with outward normals), 1/2 a ridge (a cylinder), 0 a symmetric saddle, -1/2 a valley, -1 a cup. NaN where
/// the surface is flat at the scale of the fit (curvedness <= kUmbilicTolerance / t: a plane, whose curvatures are
/// rounding) and where the curvatures are.
GLS_INLINE double shapeIndex(const PrincipalCurvatures& c, double t)
{
  using std::atan2;
  if (!(curvedness(c) > kUmbilicTolerance / t))
  {
    return quietNaN<double>();
  }
  return 0.6366197723675814 * atan2(c.k1 + c.k2, c.k1 - c.k2);
}

} // namespace gls
