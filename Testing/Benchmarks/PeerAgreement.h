// How a peer's per-point results agree with GLS's on the same points: angles between normals (up to sign), and
// curvature medians and correlations. Points where either side is not finite are left out and counted.
#pragma once

#include <cstddef>
#include <vector>

/// Percentiles of the angle (degrees) between two sets of unit normals, n1 and +/- n2 taken as the same.
struct AngleAgreement
{
  double p50 = 0, p90 = 0, p99 = 0, max = 0;
  long long aboveOneDegree = 0;
  long long compared = 0; ///< points where both normals are finite
};

/// u and v interleaved (3n), the same points in the same order.
AngleAgreement angleAgreement(const std::vector<double>& u, const std::vector<double>& v);

/// The points where the two normals (up to sign) are more than `degrees` apart.
std::vector<std::size_t> pointsApartBy(const std::vector<double>& u, const std::vector<double>& v, double degrees);

/// GLS curvature against a peer's at one scale.
struct CurvatureAgreement
{
  double medianGls = 0, medianPeer = 0; ///< medians of each side
  double medianRatio = 0;               ///< median of peer / GLS over points where GLS is not 0
  double pearson = 0;                   ///< linear correlation
  double spearman = 0;                  ///< rank correlation (ties get their mean rank)
  long long compared = 0;               ///< points where both are finite
};

/// gls[i * stride] against peer[i * stride] for i < n.
CurvatureAgreement curvatureAgreement(const double* gls, const double* peer, std::size_t n, std::size_t stride);
