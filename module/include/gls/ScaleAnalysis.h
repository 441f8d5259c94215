// Per-point analyses over the sampled scales (docs/math.md): pertinent scales (local minima of nu), the continuous
// feature f(p) and the multi-scale dissimilarity Delta(p, q) with a normalized scale prior.
#pragma once

#include "gls/ScaleSample.h"

#include <string>
#include <vector>

namespace gls
{

/// Differences of nu below this (dimensionless) are rounding noise, not variation: on a perfect sphere nu is about
/// 1e-20 with random ups and downs.
constexpr double kVariationNoise = 1e-12;

/// Whether inner scale k (0 < k < S-1) is a strict local minimum of nu: nu[k] < nu[k-1] - kVariationNoise and
/// nu[k] <= nu[k+1] + kVariationNoise (false when a neighbour or nu[k] is NaN). The rule of pertinentScales.
inline bool isPertinentScale(const double* nu, int k)
{
  return nu[k] < nu[k - 1] - kVariationNoise && nu[k] <= nu[k + 1] + kVariationNoise;
}

/// Scale indices k (0 < k < S-1) where nu has a strict local minimum: nu[k] < nu[k-1] - noise and
/// nu[k] <= nu[k+1] + noise (noise = kVariationNoise; a flat bottom counts once, at its first scale); NaN neighbours
/// disqualify. Keeps the maxCount minima with the lowest nu,
/// written in increasing scale order to `out` (the scales, not indices). Returns how many were written.
int pertinentScales(const double* nu, const double* scales, int count, int maxCount, double* out);

/// One point's summary over the sampled scales: what the main job keeps of the scale space by default (every value
/// per point, none per scale). docs/math.md, "Scale summary".
struct ScaleSummary
{
  int stableIndex;          ///< index of the most stable scale; -1 when nu is NaN at every scale
  int pertinentCount;       ///< number of pertinent scales (isPertinentScale), 0 when nu is monotonic or flat
  double stableScale;       ///< the most stable scale (length): the pertinent scale of lowest nu; where there is
                            ///< none, the defined scale of lowest nu (ties within kVariationNoise: the smaller
                            ///< scale); NaN when nu is NaN at every scale
  double tau;               ///< tau at the most stable scale (length); NaN with it or where that fit is undefined
  double kappa;             ///< kappa at the most stable scale (1/length)
  double phi;               ///< phi at the most stable scale (dimensionless, [0, 1])
  double maxVariation;      ///< the largest nu over the defined scales (dimensionless); NaN when none is defined
  double maxVariationScale; ///< the scale of the largest nu (length; the smaller one on ties); NaN with it
};

/// The summary of one point from its samples and nu at `count` increasing scales.
ScaleSummary summarizeScales(const ScaleSample* samples, const double* nu, const double* scales, int count);

enum class FeatureMeasure
{
  Scale = 0,    ///< integrate in t
  LogScale = 1  ///< integrate in ln t (every octave of scales weighs the same)
};

/// f = (1/|I|) integral over I of tanh(nu/sigma) (trapezoid over the sampled scales, in t or ln t), in [0, 1].
/// Intervals with a NaN end are left out of the integral and of |I|; NaN when no interval is left. With one scale,
/// f = tanh(nu_0/sigma).
double continuousFeature(const double* nu, const double* scales, int count, double sigma, FeatureMeasure measure);

/// The smallest sigma the data-relative rule may choose (dimensionless): nu below it is no variation. On a perfect
/// sphere or plane nu is about 1e-20, so f stays 0 there whatever the data-relative rule would pick.
constexpr double kMinimumRelativeSigma = 1e-3;

/// The data-relative sigma: the value at which the median of continuousFeature over the given rows (`rows` points,
/// nu at `count` scales each, row-major; rows whose feature is NaN are left out) equals `targetMedian` (in (0, 1)),
/// found by bisection in log sigma to 1e-6 relative; never below kMinimumRelativeSigma (then the median is below the
/// target: the data hardly varies). NaN when no row has a defined feature.
double sigmaForMedianFeature(const std::vector<double>& nu, std::size_t rows, const double* scales, int count,
  FeatureMeasure measure, double targetMedian);

enum class ScalePriorShape
{
  Box = 0,          ///< h = 1 on [minScale, maxScale]
  LogGaussian = 1   ///< Gaussian in ln t, centred at sqrt(min max), standard deviation (ln max - ln min) / 4
};

/// Normalized prior weights h_i (sum 1) over the sampled scales, or an empty vector and a reason in `why` when no
/// sampled scale gets a positive weight.
std::vector<double> scalePrior(
  const std::vector<double>& scales, ScalePriorShape shape, double minScale, double maxScale, std::string& why);

/// Delta(p, q) = sum_i delta_{p,q}(t_i) h_i, over the scales where both fits are valid, with h renormalized over
/// those scales; NaN when none is valid.
double multiScaleDissimilarity(
  const ScaleSample* p, const ScaleSample* q, const std::vector<double>& scales, const std::vector<double>& prior);

} // namespace gls
