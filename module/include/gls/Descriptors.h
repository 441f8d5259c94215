// Quantities derived from ScaleSamples (docs/math.md): the geometric variation nu (eq. 5) and the pairwise
// dissimilarity delta (eq. 6). Both are dimensionless and invariant to rigid motion and uniform scaling.
#pragma once

#include "gls/Numeric.h"
#include "gls/ScaleSample.h"

namespace gls
{

/// Weights of the three terms of nu (default 1, 1, 1).
struct VariationWeights
{
  double tau = 1.0;
  double eta = 1.0;
  double kappa = 1.0;
};

/// nu(p, t) = w_tau dtau^2 + w_eta t^2 |deta|^2 + w_kappa t^4 dkappa^2; NaN for an invalid sample.
GLS_INLINE double geometricVariation(const ScaleSample& s, double t, const VariationWeights& w)
{
  if (!s.valid)
  {
    return quietNaN<double>();
  }
  const double t2 = t * t;
  return w.tau * s.dtau * s.dtau + w.eta * t2 * squaredNorm(s.deta) + w.kappa * t2 * t2 * s.dkappa * s.dkappa;
}

/// delta(a, b) at a common scale t: (tau_a/t - tau_b/t)^2 + (t kappa_a - t kappa_b)^2 + (phi_a - phi_b)^2.
/// eta is left out on purpose (rotation invariance). NaN if either sample is invalid.
GLS_INLINE double pairDissimilarity(const ScaleSample& a, const ScaleSample& b, double t)
{
  if (!a.valid || !b.valid)
  {
    return quietNaN<double>();
  }
  const double dt = (a.tau - b.tau) / t;
  const double dk = t * (a.kappa - b.kappa);
  const double dp = a.phi - b.phi;
  return dt * dt + dk * dk + dp * dp;
}

} // namespace gls
