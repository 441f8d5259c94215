// A moment set: the values f whose weighted sums sum w_i f_i a fit consumes, declared once with every rule the engine
// needs to sum them, and the fit of one scale from those sums (docs/architecture.md, "How to add a fit"). Host/device.
// OrientedSphereMoments is the one the filters run. A set is a type with:
// - kValues, its values (the last one always |x|^2, which the one pass keeps as the moments of d^2), kOmegaValues (how
//   many of the last values before |x|^2 are summed weighted by the spatial derivative's omega = (4/t^2)(1 - d^2/t^2)
//   only: the kernels keep two moments of them, and the fit gets their omega-weighted sums in v), pointValues (a
//   point's values), Sample and fit (the fit of scale t from the values weighted by w and by dw/dt): all the exact
//   evaluation needs. Its kernels take the set as a template parameter and derive their bins, vector adds and fits
//   from it (MomentBins.h, PointScaleSpace.h, src/OnePassKernelBody.h); Testing/Core/TestFitWithAnExtraSum.cpp runs a
//   test-only set with one more value through them.
// - shiftValues (a move of origin, closed over its values), Cell (what a pyramid cell keeps) with addPointToCell and
//   addChildToCell (its rules for one point and for a child cell), and cellValues (a cell's sums of every value and
//   their gradient): what the multi-resolution evaluation needs. Its layout (AggregateMomentsT), the reference walk
//   (MultiresolutionReferenceWalk.h, the CUDA kernel's loop) and the CPU kernel (src/multiresolution/
//   MultiresolutionKernelBody.h) take the set and its cells; the pyramid stores the oriented sphere's cells, and
//   summedCellsOf (MultiresolutionCellSums.h) forms another set's over it by the build's own rule. A set with
//   omega-values also gives shiftWeightedValues (the move of its weighted sums, the CPU kernel applies it per scale).
//   Testing/Core/TestMomentSet.cpp checks every rule of every value against pointValues.
#pragma once

#include "gls/Numeric.h"
#include "gls/SphereFit.h"
#include "gls/WeightedSums.h"

namespace gls
{

/// The fitted values f of a point at local position x (length) with unit normal n, in the order every layout keeps.
enum FitValue : int
{
  kOne = 0,               ///< 1: the sums count the neighbours
  kPositionX,             ///< x (length)
  kPositionY,
  kPositionZ,
  kNormalX,               ///< n
  kNormalY,
  kNormalZ,
  kPositionDotNormal,     ///< x . n (length)
  kSquaredPosition,       ///< |x|^2 (length^2): d^2 for a point, so the one pass does not store it (MomentBins.h)
  kFitValues              ///< how many
};

/// A count of doubles rounded up to whole 64-byte lines (the layouts' padding).
constexpr int wholeCacheLines(int doubles)
{
  return (doubles + 7) / 8 * 8;
}

/// Where the fit reads each value: the sums weighted by w (v) into s, and by dw/dt (dv) into ds.
GLS_INLINE void toWeightedSums(const double* v, const double* dv, WeightedSums& s, WeightedSums& ds)
{
  s.W = v[kOne];
  s.P = { v[kPositionX], v[kPositionY], v[kPositionZ] };
  s.N = { v[kNormalX], v[kNormalY], v[kNormalZ] };
  s.PN = v[kPositionDotNormal];
  s.PP = v[kSquaredPosition];
  ds.W = dv[kOne];
  ds.P = { dv[kPositionX], dv[kPositionY], dv[kPositionZ] };
  ds.N = { dv[kNormalX], dv[kNormalY], dv[kNormalZ] };
  ds.PN = dv[kPositionDotNormal];
  ds.PP = dv[kSquaredPosition];
}

/// What a cell of the multi-resolution pyramid keeps of its m points q_i (unit normals n_i) so that cellValues can
/// form every value's sums over them and their gradient: exact sums about the centroid c, y_i = q_i - c, up to the
/// order the values need (one more power of y than the value has, for the gradient). An empty cell (count 0) has no
/// centroid and is never sampled.
struct PyramidCell
{
  Vec3 centroid;                 ///< c, the mean position (length)
  Vec3 normalSum;                ///< sum n_i
  double count;                  ///< m
  double offsetOffset[6];        ///< sum y y^T as xx, xy, xz, yy, yz, zz (length^2); its trace is sum |y|^2
  double offsetNormal[9];        ///< sum y n^T, [3 a + b] = sum y_a n_b (length); its trace is sum y . n
  Vec3 offsetOffsetDotNormal;    ///< sum y (y . n) (length^2)
  Vec3 offsetSquaredOffset;      ///< sum y |y|^2 (length^3)
};

/// sum |y|^2 over the cell's points (length^2).
GLS_INLINE double spreadOf(const PyramidCell& c)
{
  return c.offsetOffset[0] + c.offsetOffset[3] + c.offsetOffset[5];
}

/// sum y . n over the cell's points (length).
GLS_INLINE double offsetDotNormalOf(const PyramidCell& c)
{
  return c.offsetNormal[0] + c.offsetNormal[4] + c.offsetNormal[8];
}

/// out = s v for the symmetric 3x3 s stored as xx, xy, xz, yy, yz, zz, written out (the cells' second moments and
/// the curvature set's third moments contracted with one direction).
GLS_FORCE_INLINE void symmetricTimes(const double* s, const double* v, double* out)
{
  out[0] = s[0] * v[0] + s[1] * v[1] + s[2] * v[2];
  out[1] = s[1] * v[0] + s[3] * v[1] + s[4] * v[2];
  out[2] = s[2] * v[0] + s[4] * v[1] + s[5] * v[2];
}

/// (sum y y^T) v.
GLS_INLINE Vec3 offsetOffsetTimes(const PyramidCell& c, const Vec3& v)
{
  const double in[3] = { v.x, v.y, v.z };
  double out[3];
  symmetricTimes(c.offsetOffset, in, out);
  return { out[0], out[1], out[2] };
}

/// (sum y n^T) v = sum y (n . v).
GLS_INLINE Vec3 offsetNormalTimes(const PyramidCell& c, const Vec3& v)
{
  const double* s = c.offsetNormal;
  return { s[0] * v.x + s[1] * v.y + s[2] * v.z, s[3] * v.x + s[4] * v.y + s[5] * v.z,
    s[6] * v.x + s[7] * v.y + s[8] * v.z };
}

/// (sum y n^T)^T v = sum n (y . v).
GLS_INLINE Vec3 normalOffsetTimes(const PyramidCell& c, const Vec3& v)
{
  const double* s = c.offsetNormal;
  return { s[0] * v.x + s[3] * v.y + s[6] * v.z, s[1] * v.x + s[4] * v.y + s[7] * v.z,
    s[2] * v.x + s[5] * v.y + s[8] * v.z };
}

/// The oriented sphere's moment set (the fit the filters run, SphereFit.h): its values (FitValue) and their rules.
/// The kernels take a set as a template parameter and use these members; a set of another fit declares the same.
struct OrientedSphereMoments
{
  static constexpr int kValues = kFitValues; ///< how many values; the last is |x|^2 (d^2 for a point)
  static constexpr int kOmegaValues = 0;     ///< how many before |x|^2 are summed weighted by omega only (none)
  using Cell = PyramidCell;                  ///< what a pyramid cell keeps for the values' cell rules
  using Sample = ScaleSample;                ///< what the fit gives at one scale

  /// The values f of one point at local position x (d2 = |x|^2) with normal n.
  GLS_INLINE static void pointValues(const Vec3& x, double d2, const Vec3& n, double* f)
  {
    f[kOne] = 1.0;
    f[kPositionX] = x.x;
    f[kPositionY] = x.y;
    f[kPositionZ] = x.z;
    f[kNormalX] = n.x;
    f[kNormalY] = n.y;
    f[kNormalZ] = n.z;
    f[kPositionDotNormal] = dot(x, n);
    f[kSquaredPosition] = d2;
  }

  /// Moves sums of f from coordinates about o to coordinates about p (x_p = x_o + u, u = o - p, uu = |u|^2): sum x
  /// gains u sum 1, sum x.n gains u . sum n, sum |x|^2 gains 2 u . sum x + |u|^2 sum 1. Exact algebra, whatever
  /// weights the sums carry (they are the same for every value of a point).
  GLS_INLINE static void shiftValues(const Vec3& u, double uu, double* f)
  {
    const double W = f[kOne];
    const Vec3 P{ f[kPositionX], f[kPositionY], f[kPositionZ] };
    const Vec3 N{ f[kNormalX], f[kNormalY], f[kNormalZ] };
    f[kPositionX] += u.x * W;
    f[kPositionY] += u.y * W;
    f[kPositionZ] += u.z * W;
    f[kPositionDotNormal] += dot(u, N);
    f[kSquaredPosition] += 2.0 * dot(u, P) + uu * W;
  }

  /// Adds one point at offset y from the cell's centroid, with normal n, to the cell's centred sums (the count, the
  /// centroid and sum n are the cell's geometry: its caller forms them first).
  GLS_INLINE static void addPointToCell(PyramidCell& cell, const Vec3& y, const Vec3& n)
  {
    const double yy[6] = { y.x * y.x, y.x * y.y, y.x * y.z, y.y * y.y, y.y * y.z, y.z * y.z };
    for (int k = 0; k < 6; ++k)
    {
      cell.offsetOffset[k] += yy[k];
    }
    const double yv[3] = { y.x, y.y, y.z }, nv[3] = { n.x, n.y, n.z };
    for (int a = 0; a < 3; ++a)
    {
      for (int b = 0; b < 3; ++b)
      {
        cell.offsetNormal[3 * a + b] += yv[a] * nv[b];
      }
    }
    cell.offsetOffsetDotNormal = cell.offsetOffsetDotNormal + dot(y, n) * y;
    cell.offsetSquaredOffset = cell.offsetSquaredOffset + squaredNorm(y) * y;
  }

  /// Adds a child cell whose centroid is at d from the cell's to the cell's centred sums (y = y_k + d for the child's
  /// points, sum y_k = 0): sum y y^T gains C_k + m_k d d^T; sum y n^T gains N_k + d (sum n)_k^T; sum y (y . n) gains
  /// T_k + N_k d + d tr(N_k) + d (d . (sum n)_k); sum y |y|^2 gains Q_k + 2 C_k d + tr(C_k) d + m_k |d|^2 d.
  GLS_INLINE static void addChildToCell(PyramidCell& cell, const PyramidCell& child, const Vec3& d)
  {
    const double mk = child.count;
    const double dd[6] = { d.x * d.x, d.x * d.y, d.x * d.z, d.y * d.y, d.y * d.z, d.z * d.z };
    for (int i = 0; i < 6; ++i)
    {
      cell.offsetOffset[i] += child.offsetOffset[i] + mk * dd[i];
    }
    const double dv[3] = { d.x, d.y, d.z };
    const double nv[3] = { child.normalSum.x, child.normalSum.y, child.normalSum.z };
    for (int a = 0; a < 3; ++a)
    {
      for (int b = 0; b < 3; ++b)
      {
        cell.offsetNormal[3 * a + b] += child.offsetNormal[3 * a + b] + dv[a] * nv[b];
      }
    }
    const Vec3 Nd = offsetNormalTimes(child, d);
    cell.offsetOffsetDotNormal = cell.offsetOffsetDotNormal + child.offsetOffsetDotNormal + Nd +
      (offsetDotNormalOf(child) + dot(d, child.normalSum)) * d;
    const Vec3 Cd = offsetOffsetTimes(child, d);
    cell.offsetSquaredOffset = cell.offsetSquaredOffset + child.offsetSquaredOffset + 2.0 * Cd +
      (spreadOf(child) + mk * squaredNorm(d)) * d;
  }

  /// A cell's sums of every value over its points, in coordinates about an origin at -x from its centroid (x = c - o):
  /// F = sum f(x + y_i, n_i); and their gradient along a (length): H = sum (a . y_i) f(x + y_i, n_i). H[kOne] = 0,
  /// since sum y_i = 0.
  GLS_INLINE static void cellValues(const PyramidCell& cell, const Vec3& x, const Vec3& a, double* F, double* H)
  {
    const double m = cell.count;
    const Vec3 Ca = offsetOffsetTimes(cell, a);
    const Vec3 Na = normalOffsetTimes(cell, a);
    F[kOne] = m;
    F[kPositionX] = m * x.x;
    F[kPositionY] = m * x.y;
    F[kPositionZ] = m * x.z;
    F[kNormalX] = cell.normalSum.x;
    F[kNormalY] = cell.normalSum.y;
    F[kNormalZ] = cell.normalSum.z;
    F[kPositionDotNormal] = offsetDotNormalOf(cell) + dot(x, cell.normalSum);
    F[kSquaredPosition] = spreadOf(cell) + m * squaredNorm(x);
    H[kOne] = 0.0;
    H[kPositionX] = Ca.x;
    H[kPositionY] = Ca.y;
    H[kPositionZ] = Ca.z;
    H[kNormalX] = Na.x;
    H[kNormalY] = Na.y;
    H[kNormalZ] = Na.z;
    H[kPositionDotNormal] = dot(x, Na) + dot(a, cell.offsetOffsetDotNormal);
    H[kSquaredPosition] = 2.0 * dot(x, Ca) + dot(a, cell.offsetSquaredOffset);
  }

  /// The fit of scale t from the values weighted by w (v) and by dw/dt (dv), over `neighbors` points (the sphere's
  /// needs no t: a fit that weighs its values otherwise, such as a spatial derivative's, does).
  GLS_INLINE static Sample fit(const double* v, const double* dv, double, double neighbors, double minNeighbors)
  {
    WeightedSums s, ds;
    toWeightedSums(v, dv, s, ds);
    return fitOrientedSphere(s, ds, neighbors, minNeighbors);
  }
};

} // namespace gls
