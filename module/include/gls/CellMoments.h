// What a cell of the multi-resolution pyramid keeps of its points, and the sample it makes for an evaluation point
// (docs/math.md, "Multi-resolution evaluation"), host/device.
//
// A cell keeps the exact sums of its points q_i (unit normals n_i) about their centroid c, y_i = q_i - c, that the
// moment set asks for (PyramidCell in MomentSet.h, which also says how they form the sums of every fitted value). The
// sample of a cell for an evaluation point p weights its points with a linear field W + g . y_i, the first-order
// expansion of the GLS weight across the cell, and spreads their squared distances |q_i - p|^2 uniformly over an
// interval of the right mean and variance when it bins them into the scale shells. Every sum the sample adds is an
// exact sum over the cell's points with one weight per point, the same for every summed value, so the oriented sphere
// fit still recovers a sphere or a plane exactly.
#pragma once

#include "gls/AggregateMoments.h"
#include "gls/MomentSet.h"
#include "gls/Numeric.h"
#include "gls/PointScaleSpace.h"
#include "gls/StoredPoints.h"

#include <cstdint>

namespace gls
{

/// The sums of the points [first, last) (at least one) that a cell of the moment set Set keeps (Set::Cell), their
/// centroid formed about `reference` (a point near them, such as their cube's corner, so that far coordinates lose no
/// precision). The build stores these for the cells of its lowest summed level and the walks form them for finer
/// cells, with the same formulas. Inlined into its caller: the CPU kernels' AVX2 builds form the principal
/// curvatures' cells so (src/KernelSetCalls.h), with fused multiply-adds, where the oriented sphere's are formed in
/// its out-of-line cellMoments, as they always were (its samples keep their bits); momentsOfPoints is the same, left
/// to the compiler (the build's summed cells).
template <typename Set = OrientedSphereMoments>
GLS_FORCE_INLINE void formCellOfPoints(const StoredPoints& points, std::uint32_t first, std::uint32_t last,
  const Vec3& reference, typename Set::Cell& cell)
{
  double count = 0.0;
  Vec3 offset{ 0.0, 0.0, 0.0 }, normalSum{ 0.0, 0.0, 0.0 };
  for (std::uint32_t i = first; i < last; ++i)
  {
    count += 1.0;
    offset = offset + (points.position(i) - reference);
    normalSum = normalSum + points.normal(i);
  }
  cell = typename Set::Cell{};
  cell.centroid = reference + (1.0 / count) * offset;
  cell.normalSum = normalSum;
  cell.count = count;
  for (std::uint32_t i = first; i < last; ++i)
  {
    Set::addPointToCell(cell, points.position(i) - cell.centroid, points.normal(i));
  }
}

template <typename Set = OrientedSphereMoments>
GLS_INLINE void momentsOfPoints(const StoredPoints& points, std::uint32_t first, std::uint32_t last,
  const Vec3& reference, typename Set::Cell& cell)
{
  formCellOfPoints<Set>(points, first, last, reference, cell);
}

/// The sums of a parent cell from those of its `count` children (in order), about its new centroid c formed about
/// `reference` (its cube's corner): Set::addChildToCell for each child, d = c_k - c. The build forms the cells above
/// the lowest summed level so.
template <typename Set = OrientedSphereMoments>
GLS_INLINE void mergeChildren(const typename Set::Cell* children, std::uint32_t count, const Vec3& reference,
  typename Set::Cell& cell)
{
  double m = 0.0;
  Vec3 offset{ 0.0, 0.0, 0.0 }, normalSum{ 0.0, 0.0, 0.0 };
  for (std::uint32_t k = 0; k < count; ++k)
  {
    m += children[k].count;
    offset = offset + children[k].count * (children[k].centroid - reference);
    normalSum = normalSum + children[k].normalSum;
  }
  cell = typename Set::Cell{};
  cell.centroid = reference + (1.0 / m) * offset;
  cell.normalSum = normalSum;
  cell.count = m;
  for (std::uint32_t k = 0; k < count; ++k)
  {
    Set::addChildToCell(cell, children[k], children[k].centroid - cell.centroid);
  }
}

/// One cell as a sample of an evaluation point p, in local coordinates about an origin o (the host/device loop:
/// o = p; the CPU kernel: o = the corner of p's walk region, its bins moved to p afterwards), for the moment set S.
template <typename S>
struct CellSampleT
{
  using Set = S;
  /// sums and gradient hold kValues values, then zeros up to a row of the moments (AggregateMomentsT::kStride).
  static constexpr int kStride = AggregateMomentsT<S>::kStride;
  /// F: the exact sums of the fitted values f (MomentSet.h) over the cell's points, x = q - o.
  double sums[kStride];
  /// H: sum (a . y_i) f_i, with a = c - (the walk region's centre): what the sums gain when each point is weighted
  /// in proportion to a . y_i, the first-order variation of |q_i - p|^2 across the cell (a stands for c - p for
  /// every point of the region). H[0] = 0: the field moves weight within the cell, it adds none.
  double gradient[kStride];
  /// sum |y|^2 / m: the mean of |q_i - p|^2 exceeds |c - p|^2 by this (length^2).
  double spreadPerPoint;
  /// sqrt(3 V), V = 4 a^T (sum y y^T) a / m: the half-width of the uniform distribution with the variance of
  /// 2 a . y_i, over which the squared distances |q_i - p|^2 are spread when the cell is binned (length^2).
  double halfWidth;
};

/// The oriented sphere's cell sample.
using CellSample = CellSampleT<OrientedSphereMoments>;

/// The half-width of a cell's spread of squared distances seen along `direction` (CellSample::halfWidth):
/// sqrt(3 V), V = 4 a^T C a / m the variance of 2 a . y over its points. (Every set's cell keeps the oriented
/// sphere's statistics, which place it: its Cell is a PyramidCell or derives from one.)
GLS_INLINE double spreadHalfWidth(const PyramidCell& cell, const Vec3& direction)
{
  const double variance = 4.0 * dot(direction, offsetOffsetTimes(cell, direction)) / cell.count;
  return variance > 0.0 ? squareRoot(3.0 * variance) : 0.0;
}

/// The sample of `cell` in coordinates about `origin`, with `direction` a = c - (the walk region's centre). Inlined
/// into its caller (formCellOfPoints says why); makeCellSample is the same, left to the compiler.
template <typename S>
GLS_FORCE_INLINE void formCellSample(
  const typename S::Cell& cell, const Vec3& origin, const Vec3& direction, CellSampleT<S>& s)
{
  S::cellValues(cell, cell.centroid - origin, direction, s.sums, s.gradient);
  for (int j = S::kValues; j < CellSampleT<S>::kStride; ++j)
  {
    s.sums[j] = s.gradient[j] = 0.0;
  }
  s.spreadPerPoint = spreadOf(cell) / cell.count;
  s.halfWidth = spreadHalfWidth(cell, direction);
}

template <typename S>
GLS_INLINE void makeCellSample(
  const typename S::Cell& cell, const Vec3& origin, const Vec3& direction, CellSampleT<S>& s)
{
  formCellSample(cell, origin, direction, s);
}

/// A spread narrower than this fraction of its upper end is not split: the sample goes whole to the shell of its
/// mean (its points' weights and their t-derivatives vanish on a scale's sphere, so the misplaced part is of the
/// order of this fraction).
constexpr double kNarrowestSpread = 1e-4;

/// A cell's share of one scale shell: A_j += m[j] F + c[j] H (j = 0, 1, 2).
struct ShellShare
{
  double m[3]; ///< the share's moments of s = |q - p|^2: E[1; shell], E[s; shell], E[s^2; shell] over the points
  double c[3]; ///< the gradient's: E[s^j (s - mean); shell] / (2 sigma^2), sigma^2 = Var(a . y) = V / 4
};

/// The variance V = half^2 / 3 of squared distances spread uniformly over [mean - half, mean + half] (length^4).
GLS_INLINE double spreadVariance(double half)
{
  return half * half * (1.0 / 3.0);
}

/// The share of a whole cell, within one shell: m = (1, mean, mean^2 + V), c = (0, 2, 4 mean), V = spreadVariance.
/// (E[w] F + 2 w'(mean) H for the weight w = 1 + c1 s + c2 s^2, E[w] its mean over the spread: the sums of
/// (w(mean) + 2 w'(mean) a . y_i) f_i, exact to the first order in y.)
GLS_INLINE ShellShare wholeShare(double mean, double half)
{
  return { { 1.0, mean, mean * mean + spreadVariance(half) }, { 0.0, 2.0, 4.0 * mean } };
}

/// The constants of a spread's pieces: its density rho = 1 / (2 half) and rho / (2 sigma^2) = 3 / half^3
/// (2 sigma^2 = V / 2 = half^2 / 6).
struct SpreadDensity
{
  double rho, gradientScale;
};

GLS_INLINE SpreadDensity spreadDensity(double half)
{
  return { 1.0 / (2.0 * half), 3.0 / (half * half * half) };
}

/// The share of the part [u, w] of a spread [mean - half, mean + half] (half > 0, density `density`): its points are
/// those whose a . y = (s - mean) / 2 lies there, so their f regresses on a . y as F / m + (a . y) H / (m sigma^2);
/// integrated over the uniform spread in d = s - mean. The CPU kernel's AVX2 build forms the same arithmetic for four
/// cells at a time (pieceSharesAvx2 in src/multiresolution/MultiresolutionPieces.h; a change here goes there too: the
/// test of the CPU kernel against the host/device loop fails otherwise).
GLS_INLINE ShellShare pieceShare(double mean, const SpreadDensity& density, double u, double w)
{
  const double rho = density.rho;
  const double gradientScale = density.gradientScale;
  const double d0 = u - mean, d1 = w - mean;
  const double width = w - u;
  const double i1 = width * (d1 + d0) * 0.5;                          // int d
  const double i2 = width * (d1 * d1 + d1 * d0 + d0 * d0) * (1.0 / 3.0); // int d^2
  const double i3 = width * (d1 + d0) * (d1 * d1 + d0 * d0) * 0.25;    // int d^3
  ShellShare share;
  share.m[0] = width * rho;
  share.m[1] = width * (w + u) * 0.5 * rho;
  share.m[2] = width * (w * w + w * u + u * u) * (1.0 / 3.0) * rho;
  share.c[0] = gradientScale * i1;
  share.c[1] = gradientScale * (i2 + mean * i1);
  share.c[2] = gradientScale * (i3 + 2.0 * mean * i2 + mean * mean * i1);
  return share;
}

/// How a share changes as the spread moves: the first and second derivatives of its m[j] and c[j] with respect to
/// the spread's mean, its half-width held (the linearized cells of docs/math.md, "Linearized far cells").
struct ShellShareExpansion
{
  ShellShare value, slope, curvature;
};

/// Within one shell: m' = (0, 1, 2 mean), c' = (0, 0, 4); m'' = (0, 0, 2), c'' = 0.
GLS_INLINE ShellShareExpansion wholeShareExpansion(double mean, double half)
{
  return { wholeShare(mean, half), { { 0.0, 1.0, 2.0 * mean }, { 0.0, 0.0, 4.0 } },
    { { 0.0, 0.0, 2.0 }, { 0.0, 0.0, 0.0 } } };
}

/// The derivative of pieceShare(mean, density, u, w) with respect to mean: an end of the piece that is an end of
/// the spread moves with it, one that is a scale's sphere (lowFixed, highFixed) stays. With d0 = u - mean,
/// d1 = w - mean and [.] = 1 for a fixed end: m0' = rho ([u] - [w]), m1' = rho (w - u - w [w] + u [u]),
/// m2' = rho (w^2 - u^2 - w^2 [w] + u^2 [u]); c0' = g (d0 [u] - d1 [w]), c1' = g (int d - w d1 [w] + u d0 [u]),
/// c2' = g (2 (int d^2 + mean int d) - w^2 d1 [w] + u^2 d0 [u]), g = density.gradientScale.
GLS_INLINE ShellShare pieceShareSlope(
  double mean, const SpreadDensity& density, double u, double w, bool lowFixed, bool highFixed)
{
  const double rho = density.rho;
  const double g = density.gradientScale;
  const double d0 = u - mean, d1 = w - mean;
  const double width = w - u;
  const double lu = lowFixed ? 1.0 : 0.0, hw = highFixed ? 1.0 : 0.0;
  const double i1 = width * (d1 + d0) * 0.5;
  const double i2 = width * (d1 * d1 + d1 * d0 + d0 * d0) * (1.0 / 3.0);
  ShellShare slope;
  slope.m[0] = rho * (lu - hw);
  slope.m[1] = rho * (width - w * hw + u * lu);
  slope.m[2] = rho * ((w * w - u * u) - w * w * hw + u * u * lu);
  slope.c[0] = g * (d0 * lu - d1 * hw);
  slope.c[1] = g * (i1 - w * d1 * hw + u * d0 * lu);
  slope.c[2] = g * (2.0 * (i2 + mean * i1) - w * w * d1 * hw + u * u * d0 * lu);
  return slope;
}

/// The second derivative of pieceShare with respect to mean (pieceShareSlope differentiated again; [.]' = 1 - [.]
/// for an end that moves): m0'' = 0, m1'' = rho ([u] - [w]), m2'' = 2 rho (w [w]' - u [u]'); c0'' = g ([w] - [u]),
/// c1'' = g (d1 [w]' - d0 [u]' - (w - u) + w [w] - u [u]), c2'' = g (2 (w d1 [w]' - u d0 [u]') - (w^2 - u^2) +
/// w^2 [w] - u^2 [u]).
GLS_INLINE ShellShare pieceShareCurvature(
  double mean, const SpreadDensity& density, double u, double w, bool lowFixed, bool highFixed)
{
  const double rho = density.rho;
  const double g = density.gradientScale;
  const double d0 = u - mean, d1 = w - mean;
  const double lu = lowFixed ? 1.0 : 0.0, hw = highFixed ? 1.0 : 0.0;
  const double lm = 1.0 - lu, hm = 1.0 - hw;
  ShellShare curvature;
  curvature.m[0] = 0.0;
  curvature.m[1] = rho * (lu - hw);
  curvature.m[2] = 2.0 * rho * (w * hm - u * lm);
  curvature.c[0] = g * (hw - lu);
  curvature.c[1] = g * ((d1 * hm - d0 * lm) - (w - u) + w * hw - u * lu);
  curvature.c[2] = g * (2.0 * (w * d1 * hm - u * d0 * lm) - (w * w - u * u) + w * w * hw - u * u * lu);
  return curvature;
}

/// The pieces of a sample whose squared distances from p are spread uniformly over [mean - half, mean + half], cut
/// by the scale shells below r2 (the largest squared scale): whole(k) for a spread within shell k or narrower than
/// kNarrowestSpread (in the shell of its mean), else piece(k, density, u, w, lowFixed, highFixed) for each part
/// [u, w] of shell k, lowFixed / highFixed where that end is a scale's sphere rather than an end of the spread.
template <typename Whole, typename Piece>
GLS_FORCE_INLINE void forEachPieceOfSpread(
  const ScaleBinning& b, double r2, double mean, double half, Whole&& whole, Piece&& piece)
{
  const double lo = mean - half, hi = mean + half;
  if (!(half > kNarrowestSpread * hi))
  {
    if (mean < r2)
    {
      whole(firstScaleHolding(b, mean));
    }
    return;
  }
  if (!(lo < r2))
  {
    return;
  }
  const int first = firstScaleHolding(b, lo > 0.0 ? lo : 0.0);
  const int last = hi < r2 ? firstScaleHolding(b, hi) : b.count - 1;
  if (first == last && hi < r2)
  {
    whole(first);
    return;
  }
  const SpreadDensity density = spreadDensity(half);
  for (int k = first; k <= last; ++k)
  {
    const bool lowFixed = k != first;
    const bool highFixed = !(k == last && hi < b.squaredScales[k]);
    const double u = lowFixed ? b.squaredScales[k - 1] : lo;
    const double w = highFixed ? b.squaredScales[k] : hi;
    if (w > u)
    {
      piece(k, density, u, w, lowFixed, highFixed);
    }
  }
}

/// Splits a sample whose squared distances from p are spread uniformly over [mean - half, mean + half] into the
/// scale shells it meets below r2 (the largest squared scale): calls add(k, share) for each. A sample within one
/// shell (the common case), or narrower than kNarrowestSpread, makes one call with its wholeShare.
template <typename Add>
GLS_INLINE void forEachShellOfSpread(const ScaleBinning& b, double r2, double mean, double half, Add&& add)
{
  forEachPieceOfSpread(
    b, r2, mean, half, [&](int k) { add(k, wholeShare(mean, half)); },
    [&](int k, const SpreadDensity& density, double u, double w, bool, bool) {
      add(k, pieceShare(mean, density, u, w));
    });
}

/// forEachShellOfSpread with each share's derivatives: add(k, expansion) (wholeShareExpansion, pieceShareSlope,
/// pieceShareCurvature).
template <typename Add>
GLS_FORCE_INLINE void forEachShellOfSpreadExpanded(
  const ScaleBinning& b, double r2, double mean, double half, Add&& add)
{
  forEachPieceOfSpread(
    b, r2, mean, half, [&](int k) GLS_INLINE_LAMBDA { add(k, wholeShareExpansion(mean, half)); },
    [&](int k, const SpreadDensity& density, double u, double w, bool lowFixed, bool highFixed) GLS_INLINE_LAMBDA {
      add(k,
        ShellShareExpansion{ pieceShare(mean, density, u, w),
          pieceShareSlope(mean, density, u, w, lowFixed, highFixed),
          pieceShareCurvature(mean, density, u, w, lowFixed, highFixed) });
    });
}

/// The share of a spread moved from the mean it was expanded at: value + delta slope + quadratic curvature, with
/// delta the move of the mean and quadratic (about delta^2 / 2) the second-order term the caller keeps.
GLS_INLINE ShellShare movedShare(const ShellShareExpansion& e, double delta, double quadratic)
{
  ShellShare moved;
  for (int j = 0; j < 3; ++j)
  {
    moved.m[j] = e.value.m[j] + delta * e.slope.m[j] + quadratic * e.curvature.m[j];
    moved.c[j] = e.value.c[j] + delta * e.slope.c[j] + quadratic * e.curvature.c[j];
  }
  return moved;
}

/// Adds a cell's share of one shell: A_j += m_j F + c_j H (docs/math.md).
template <typename S>
GLS_INLINE void addCellShare(AggregateMomentsT<S>& a, const CellSampleT<S>& s, const ShellShare& share)
{
  constexpr int V = S::kValues, R = AggregateMomentsT<S>::kStride;
  for (int j = 0; j < V; ++j)
  {
    a.m[j] += share.m[0] * s.sums[j] + share.c[0] * s.gradient[j];
    a.m[R + j] += share.m[1] * s.sums[j] + share.c[1] * s.gradient[j];
    a.m[2 * R + j] += share.m[2] * s.sums[j] + share.c[2] * s.gradient[j];
  }
}

} // namespace gls
