// The scale at which a point's principal directions are most stable, and what the surface is there (docs/math.md,
// "Principal curvatures", across scales): the reduction over scales of one point's principal curvatures
// (ShapeOperator.h) that the fused filter GLS Principal Directions keeps instead of every scale.
#pragma once

#include "gls/ShapeOperator.h"

namespace gls
{

/// A scale's principal directions count where the curvatures differ by at least this fraction of the larger one,
/// k1 - k2 >= kSignificantAnisotropy max(|k1|, |k2|) (the and the tests' criterion: below it the directions
/// turn with noise).
constexpr double kSignificantAnisotropy = 0.2;

/// Koenderink's shape index range of a ridge, [3/8, 5/8] (a valley: its opposite).
constexpr double kRidgeShapeIndexLow = 0.375;
constexpr double kRidgeShapeIndexHigh = 0.625;

/// One point's steadiest principal direction over its scales.
struct StableDirection
{
  /// sqrt(t_k t_(k+1)) of the pair of consecutive scales, both anisotropic (kSignificantAnisotropy) with defined
  /// directions, whose d1 turn least per unit of log t (the first such pair on a tie); length. NaN where no pair is.
  double scale;
  /// The angle between the pair's d1 (as lines: d1 and -d1 are one direction) over ln(t_(k+1) / t_k): radians.
  double turnRate;
  /// (k1 - k2) / (|k1| + |k2|) there, the mean of the pair: dimensionless, in [0, 1] (1: one curvature is 0).
  double anisotropy;
  /// Koenderink's shape index there, the mean of the pair (ShapeOperator.h's shapeIndex): dimensionless, [-1, 1].
  double shapeIndex;
  /// d1 there: the pair's d1 summed with one sign and normalized (its largest component positive); unit.
  Vec3 direction;
  /// +1 on a ridge (shape index in [3/8, 5/8]), -1 in a valley ([-5/8, -3/8]), 0 elsewhere.
  double ridgeValley;
};

/// The steadiest direction of one point from its S principal curvatures at the increasing scales; every value NaN
/// (scale, turn rate, anisotropy, shape index, direction, ridgeValley) where no pair of consecutive scales has
/// significant anisotropy and defined directions.
StableDirection steadiestDirection(const PrincipalCurvatures* c, const double* scales, int S,
  double significance = kSignificantAnisotropy);

} // namespace gls
