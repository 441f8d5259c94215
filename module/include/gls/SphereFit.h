// Oriented algebraic sphere fit (Guennebaud & Gross, closed form), Pratt normalization and the exact analytic
// scale derivatives (docs/math.md). Input: the weighted sums s at scale t and their t-derivatives ds, in local
// coordinates around the evaluation point. Output: a ScaleSample; NaN everywhere (valid = false) when the fit is
// undefined: W <= 0, fewer than minNeighbors neighbours, zero gradient, phi <= 0, or any non-finite value.
#pragma once

#include "gls/Numeric.h"
#include "gls/ScaleSample.h"
#include "gls/WeightedSums.h"

namespace gls
{

/// Relative threshold under which the spatial variance term `deno` is treated as zero (all neighbours at one place).
constexpr double kDegenerateSpreadEpsilon = 1e-12;

template <typename T>
GLS_INLINE ScaleSampleT<T> invalidSample(T neighbors)
{
  const T nan = quietNaN<T>();
  ScaleSampleT<T> r;
  r.tau = r.kappa = r.phi = r.dtau = r.dkappa = nan;
  r.eta = { nan, nan, nan };
  r.deta = { nan, nan, nan };
  r.neighbors = neighbors;
  r.valid = false;
  return r;
}

template <typename T>
GLS_INLINE ScaleSampleT<T> fitOrientedSphere(
  const WeightedSumsT<T>& s, const WeightedSumsT<T>& ds, T neighbors, T minNeighbors)
{
  if (!(s.W > T(0)) || neighbors < minNeighbors)
  {
    return invalidSample<T>(neighbors);
  }
  const T invW = T(1) / s.W;
  const T PdotN = dot(s.P, s.N);
  const T PdotP = dot(s.P, s.P);
  const T nume = s.PN - PdotN * invW;
  const T deno = s.PP - PdotP * invW;
  const T spreadScale = s.PP > PdotP * invW ? s.PP : PdotP * invW;

  T uq, uc, duq, duc;
  Vec3T<T> ul, dul;
  if (absolute(deno) <= T(kDegenerateSpreadEpsilon) * spreadScale)
  {
    // All neighbours at (numerically) one place: a plane through them with the mean normal.
    const T nN = squareRoot(squaredNorm(s.N));
    if (!(nN > T(0)))
    {
      return invalidSample<T>(neighbors);
    }
    uq = T(0);
    duq = T(0);
    ul = (T(1) / nN) * s.N;
    dul = (T(1) / nN) * (ds.N - dot(ul, ds.N) * ul);
    uc = -dot(ul, s.P) * invW;
    duc = -(dot(dul, s.P) + dot(ul, ds.P) + uc * ds.W) * invW;
  }
  else
  {
    const T halfInvDeno = T(1) / (T(2) * deno);
    uq = nume * halfInvDeno;
    ul = invW * (s.N - (T(2) * uq) * s.P);
    uc = -(dot(ul, s.P) + uq * s.PP) * invW;

    const T invW2 = invW * invW;
    const T dnume = ds.PN - (dot(ds.P, s.N) + dot(s.P, ds.N)) * invW + PdotN * ds.W * invW2;
    const T ddeno = ds.PP - T(2) * dot(s.P, ds.P) * invW + PdotP * ds.W * invW2;
    duq = (dnume - T(2) * uq * ddeno) * halfInvDeno;
    dul = invW * (ds.N - (T(2) * duq) * s.P - (T(2) * uq) * ds.P - ds.W * ul);
    duc = -(dot(dul, s.P) + dot(ul, ds.P) + duq * s.PP + uq * ds.PP + uc * ds.W) * invW;
  }

  const T ulNorm2 = squaredNorm(ul);
  const T phi = ulNorm2 - T(4) * uc * uq;
  if (!(ulNorm2 > T(0)) || !(phi > T(0)))
  {
    return invalidSample<T>(neighbors);
  }
  // Four divisions and two square roots in all (their throughput bounds the cost of a fit).
  const T invSqrtPhi = T(1) / squareRoot(phi);
  const T invUlNorm = T(1) / squareRoot(ulNorm2);
  const T dphi = T(2) * dot(ul, dul) - T(4) * (duc * uq + uc * duq);
  const T halfDphiOverPhi = T(0.5) * dphi * invSqrtPhi * invSqrtPhi;

  ScaleSampleT<T> r;
  r.phi = phi;
  r.tau = uc * invSqrtPhi;
  r.kappa = T(2) * uq * invSqrtPhi;
  r.eta = invUlNorm * ul;
  r.dtau = duc * invSqrtPhi - r.tau * halfDphiOverPhi;
  r.dkappa = T(2) * duq * invSqrtPhi - r.kappa * halfDphiOverPhi;
  r.deta = invUlNorm * (dul - dot(r.eta, dul) * r.eta);
  r.neighbors = neighbors;
  r.valid = true;

  const T check = r.tau + r.kappa + r.phi + r.dtau + r.dkappa + dot(r.eta, r.eta) + dot(r.deta, r.deta);
  if (!isFinite(check))
  {
    return invalidSample<T>(neighbors);
  }
  return r;
}

} // namespace gls
