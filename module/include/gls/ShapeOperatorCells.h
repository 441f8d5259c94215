// The principal curvatures' values (ShapeOperatorMoments, ShapeOperator.h) as the multi-resolution evaluation needs
// them: their move of origin, and what a pyramid cell keeps of its points to give their sums and gradient (the rules
// of MomentSet.h for the 16 omega-values beyond the oriented sphere's). Host/device. Checked value by value against
// the points summed one by one (Testing/Core/TestMomentSet.cpp, for every set).
#pragma once

#include "gls/MomentSet.h"

namespace gls
{

/// The values of ShapeOperatorMoments after the oriented sphere's eight (kOne .. kPositionDotNormal, FitValue), in
/// this order, then |x|^2 last: its omega-values, summed weighted by omega only. The entries of x x^T and n x^T that
/// their traces give are left out.
enum ShapeOperatorValue : int
{
  kOffsetOffset = kSquaredPosition,                  ///< x x^T as xx, xy, xz, yy, yz (length^2): 5 values (zz: trace)
  kNormalOffset = kOffsetOffset + 5,                 ///< n x^T, [3 a + b] = n_a x_b for 3 a + b < 8 (length): 8
  kOffsetDotNormalOffset = kNormalOffset + 8,        ///< (x . n) x (length^2): 3 values
  kShapeOperatorSquaredPosition = kOffsetDotNormalOffset + 3, ///< |x|^2, last as in every set
  kShapeOperatorValues                               ///< how many (25)
};

/// Where the pair (a, b) of axes sits in a symmetric 3x3 stored as xx, xy, xz, yy, yz, zz (a table: these indices
/// sit in the cells' inner loops).
GLS_INLINE int pairIndex(int a, int b)
{
  constexpr int index[3][3] = { { 0, 1, 2 }, { 1, 3, 4 }, { 2, 4, 5 } };
  return index[a][b];
}

/// Where the triple (a, b, c) sits in a symmetric 3x3x3 stored as xxx, xxy, xxz, xyy, xyz, xzz, yyy, yyz, yzz, zzz.
GLS_INLINE int tripleIndex(int a, int b, int c)
{
  constexpr int index[3][3][3] = { { { 0, 1, 2 }, { 1, 3, 4 }, { 2, 4, 5 } }, { { 1, 3, 4 }, { 3, 6, 7 }, { 4, 7, 8 } },
    { { 2, 4, 5 }, { 4, 7, 8 }, { 5, 8, 9 } } };
  return index[a][b][c];
}

/// What a pyramid cell keeps for the principal curvatures' values: the oriented sphere's statistics and the third
/// moments their gradient needs, all about the centroid (y_i = q_i - c).
struct CurvatureCell : PyramidCell
{
  double offsetCubed[10];                ///< sum y_a y_b y_c (tripleIndex; length^3)
  double normalOffsetOffset[18];         ///< sum n_p y_a y_b at [6 p + pairIndex(a, b)] (length^2)
  double offsetDotNormalOffsetOffset[6]; ///< sum (y . n) y_a y_b at [pairIndex(a, b)] (length^3)
};

/// The full sum n x^T, [3 p + q] = n_p x_q, from the set's eight entries and the trace sum x . n.
GLS_INLINE void normalOffsetMatrix(const double* f, double* M)
{
  for (int k = 0; k < 8; ++k)
  {
    M[k] = f[kNormalOffset + k];
  }
  M[8] = f[kPositionDotNormal] - M[0] - M[4];
}

/// Moves the omega-values' sums from coordinates about o to about p (x_p = x_o + u), from the sums about o of 1, x, n
/// and x . n (f, before the sphere's own are moved): sum x_a x_b gains u_b sum x_a + u_a sum x_b + u_a u_b W;
/// sum n_p x_q gains u_q sum n_p; sum (x . n) x gains u sum x . n + (sum x n^T) u + u (u . sum n).
GLS_FORCE_INLINE void shiftCurvatureValues(const Vec3& u, double* f)
{
  const double W = f[kOne];
  const double P[3] = { f[kPositionX], f[kPositionY], f[kPositionZ] };
  const double N[3] = { f[kNormalX], f[kNormalY], f[kNormalZ] };
  const double U[3] = { u.x, u.y, u.z };
  double M[9];
  normalOffsetMatrix(f, M);
  const double uN = U[0] * N[0] + U[1] * N[1] + U[2] * N[2];
  const double PN = f[kPositionDotNormal];
  const int pairs[5][2] = { { 0, 0 }, { 0, 1 }, { 0, 2 }, { 1, 1 }, { 1, 2 } };
  for (int k = 0; k < 5; ++k)
  {
    const int a = pairs[k][0], b = pairs[k][1];
    f[kOffsetOffset + k] += U[b] * P[a] + U[a] * P[b] + U[a] * U[b] * W;
  }
  for (int k = 0; k < 8; ++k)
  {
    f[kNormalOffset + k] += U[k % 3] * N[k / 3];
  }
  for (int a = 0; a < 3; ++a)
  {
    // (sum x n^T) u: sum_b u_b sum n_b x_a.
    const double xnu = M[a] * U[0] + M[3 + a] * U[1] + M[6 + a] * U[2];
    f[kOffsetDotNormalOffset + a] += U[a] * PN + xnu + U[a] * uN;
  }
}

/// Adds one point at offset y from the cell's centroid, with normal n, to the third moments: its six products
/// y_a y_b (pairIndex order) times y_c, n_p and y . n, written out (the walks form finer cells from their points).
GLS_FORCE_INLINE void addPointToCurvatureCell(CurvatureCell& cell, const Vec3& y, const Vec3& n)
{
  const double yy[6] = { y.x * y.x, y.x * y.y, y.x * y.z, y.y * y.y, y.y * y.z, y.z * y.z };
  double* T = cell.offsetCubed; // xxx, xxy, xxz, xyy, xyz, xzz, yyy, yyz, yzz, zzz
  T[0] += yy[0] * y.x;
  T[1] += yy[0] * y.y;
  T[2] += yy[0] * y.z;
  T[3] += yy[1] * y.y;
  T[4] += yy[1] * y.z;
  T[5] += yy[2] * y.z;
  T[6] += yy[3] * y.y;
  T[7] += yy[3] * y.z;
  T[8] += yy[4] * y.z;
  T[9] += yy[5] * y.z;
  const double Nv[3] = { n.x, n.y, n.z };
  const double yn = dot(y, n);
  for (int ab = 0; ab < 6; ++ab)
  {
    cell.normalOffsetOffset[ab] += Nv[0] * yy[ab];
    cell.normalOffsetOffset[6 + ab] += Nv[1] * yy[ab];
    cell.normalOffsetOffset[12 + ab] += Nv[2] * yy[ab];
    cell.offsetDotNormalOffsetOffset[ab] += yn * yy[ab];
  }
}

/// Adds a child cell whose centroid is at d from the cell's to the third moments (y = y_k + d, sum y_k = 0):
/// sum y_a y_b y_c gains T_k + C_k,ab d_c + C_k,ac d_b + C_k,bc d_a + m_k d_a d_b d_c; sum n_p y_a y_b gains
/// its own + (sum n_p y_a) d_b + (sum n_p y_b) d_a + N_p d_a d_b; sum (y . n) y_a y_b gains its own and the terms of
/// (y_k . n + d . n)(y_k + d)_a (y_k + d)_b.
GLS_INLINE void addChildToCurvatureCell(CurvatureCell& cell, const CurvatureCell& child, const Vec3& d)
{
  const double D[3] = { d.x, d.y, d.z };
  const double m = child.count;
  const double* C = child.offsetOffset;
  const double* Yn = child.offsetNormal; // [3 a + p] = sum y_a n_p
  const double N[3] = { child.normalSum.x, child.normalSum.y, child.normalSum.z };
  const double O[3] = { child.offsetOffsetDotNormal.x, child.offsetOffsetDotNormal.y,
    child.offsetOffsetDotNormal.z };                           // sum (y . n) y
  const double trace = Yn[0] + Yn[4] + Yn[8];                  // sum y . n
  const double dN = D[0] * N[0] + D[1] * N[1] + D[2] * N[2];  // d . sum n
  for (int a = 0; a < 3; ++a)
  {
    for (int b = a; b < 3; ++b)
    {
      const int ab = pairIndex(a, b);
      for (int c = b; c < 3; ++c)
      {
        const int abc = tripleIndex(a, b, c);
        cell.offsetCubed[abc] += child.offsetCubed[abc] + C[ab] * D[c] + C[pairIndex(a, c)] * D[b] +
          C[pairIndex(b, c)] * D[a] + m * D[a] * D[b] * D[c];
      }
      double dNyy = 0.0, dNya = 0.0, dNyb = 0.0; // sum (d . n) y_a y_b, sum (d . n) y_a, sum (d . n) y_b
      for (int p = 0; p < 3; ++p)
      {
        cell.normalOffsetOffset[6 * p + ab] += child.normalOffsetOffset[6 * p + ab] + Yn[3 * a + p] * D[b] +
          Yn[3 * b + p] * D[a] + N[p] * D[a] * D[b];
        dNyy += D[p] * child.normalOffsetOffset[6 * p + ab];
        dNya += D[p] * Yn[3 * a + p];
        dNyb += D[p] * Yn[3 * b + p];
      }
      cell.offsetDotNormalOffsetOffset[ab] += child.offsetDotNormalOffsetOffset[ab] + O[a] * D[b] + O[b] * D[a] +
        trace * D[a] * D[b] + dNyy + dNya * D[b] + dNyb * D[a] + dN * D[a] * D[b];
    }
  }
}

/// The omega-values' sums over a cell's points in coordinates about an origin at -x from its centroid (x = c - o):
/// F = sum f(x + y_i, n_i), and their gradient along `dir`, H = sum (dir . y_i) f(x + y_i, n_i). The third moments
/// are contracted with dir once (K, L, T) and shared by the values that read them; every index is a constant (the
/// tables' lookups in loops cost 6% of the multi-resolution kernel's time).
GLS_FORCE_INLINE void curvatureCellValues(
  const CurvatureCell& cell, const Vec3& x, const Vec3& dir, double* F, double* H)
{
  const double X[3] = { x.x, x.y, x.z }, A[3] = { dir.x, dir.y, dir.z };
  const double m = cell.count;
  const double* C = cell.offsetOffset;
  const double* Yn = cell.offsetNormal; // [3 a + p] = sum y_a n_p
  const Vec3 Ca = offsetOffsetTimes(cell, dir), Na = normalOffsetTimes(cell, dir); // sum y (y . dir), sum n (y . dir)
  const double CA[3] = { Ca.x, Ca.y, Ca.z }, NA[3] = { Na.x, Na.y, Na.z };
  const double N[3] = { cell.normalSum.x, cell.normalSum.y, cell.normalSum.z };
  const double O[3] = { cell.offsetOffsetDotNormal.x, cell.offsetOffsetDotNormal.y, cell.offsetOffsetDotNormal.z };
  const double trace = Yn[0] + Yn[4] + Yn[8];
  const double xN = X[0] * N[0] + X[1] * N[1] + X[2] * N[2], xNa = X[0] * NA[0] + X[1] * NA[1] + X[2] * NA[2];
  const double aO = A[0] * O[0] + A[1] * O[1] + A[2] * O[2];
  // K[p][q] = sum (dir . y) n_p y_q; L[a] = sum (dir . y)(y . n) y_a; T: sum (dir . y) y_a y_b as xx, xy, xz, yy, yz.
  double K[3][3], L[3];
  symmetricTimes(cell.normalOffsetOffset, A, K[0]);
  symmetricTimes(cell.normalOffsetOffset + 6, A, K[1]);
  symmetricTimes(cell.normalOffsetOffset + 12, A, K[2]);
  symmetricTimes(cell.offsetDotNormalOffsetOffset, A, L);
  const double* Y = cell.offsetCubed; // xxx, xxy, xxz, xyy, xyz, xzz, yyy, yyz, yzz, zzz
  const double T[5] = { A[0] * Y[0] + A[1] * Y[1] + A[2] * Y[2], A[0] * Y[1] + A[1] * Y[3] + A[2] * Y[4],
    A[0] * Y[2] + A[1] * Y[4] + A[2] * Y[5], A[0] * Y[3] + A[1] * Y[6] + A[2] * Y[7],
    A[0] * Y[4] + A[1] * Y[7] + A[2] * Y[8] };
  // The five pairs (a, b) of kOffsetOffset: xx, xy, xz, yy, yz, at C's pairIndex 0 to 4.
  const auto offsetOffset = [&](int k, int a, int b) GLS_INLINE_LAMBDA {
    F[kOffsetOffset + k] = m * X[a] * X[b] + C[k];
    H[kOffsetOffset + k] = X[a] * CA[b] + CA[a] * X[b] + T[k];
  };
  offsetOffset(0, 0, 0);
  offsetOffset(1, 0, 1);
  offsetOffset(2, 0, 2);
  offsetOffset(3, 1, 1);
  offsetOffset(4, 1, 2);
  for (int k = 0; k < 8; ++k)
  {
    const int p = k / 3, q = k % 3;
    F[kNormalOffset + k] = N[p] * X[q] + Yn[3 * q + p];
    H[kNormalOffset + k] = NA[p] * X[q] + K[p][q];
  }
  for (int a = 0; a < 3; ++a)
  {
    // sum (x . n) y_a, sum (dir . y)(x . n) y_a
    const double xYn = X[0] * Yn[3 * a] + X[1] * Yn[3 * a + 1] + X[2] * Yn[3 * a + 2];
    const double xnyy = X[0] * K[0][a] + X[1] * K[1][a] + X[2] * K[2][a];
    F[kOffsetDotNormalOffset + a] = X[a] * (xN + trace) + xYn + O[a];
    H[kOffsetDotNormalOffset + a] = X[a] * (xNa + aO) + xnyy + L[a];
  }
}

} // namespace gls
