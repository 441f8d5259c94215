// Adaptive bandwidth (the paper's section 6, docs/math.md): per point, the smallest pertinent scale found coarse to
// fine from the geometric variation nu(p, t), then a spatial regularization over neighbouring points.
#pragma once

#include "gls/ParallelFor.h"

#include <cstddef>

namespace gls
{

/// The raw bandwidth of one point from nu at `count` strictly increasing scales. Going from the coarsest scale
/// down, the scan stops at the first pair of scales (t_k, t_k+1) where nu grows towards the finer scale faster than
/// the threshold, in the dimensionless slope  -(nu(t_k+1) - nu(t_k)) / ln(t_k+1 / t_k) > threshold  (a finite
/// difference of d nu / d ln t = t d nu / dt), or where nu(t_k) is undefined (too few neighbours); the bandwidth is
/// then t_k+1, the finest scale of the stable range above. Noise makes nu rise sharply towards fine scales; a
/// feature entering the ball makes it rise as t comes down to the feature's distance, which keeps the bandwidth
/// below it. Without any such pair the bandwidth is t_0 (nothing to smooth). NaN when nu is undefined at the
/// coarsest scale or count < 1.
double rawBandwidth(const double* nu, const double* scales, int count, double threshold);

/// Spatial regularization: out[i] = sum w_ij raw[j] / sum w_ij over the points j with finite coordinates and finite
/// raw[j] within `radius` of point i (including i), w = (1 - d^2/radius^2)^2. Points with non-finite coordinates,
/// or with no such neighbour, get NaN. radius <= 0 copies raw. xyz: n interleaved positions. Deterministic for any
/// thread count. Returns false if aborted (out is then incomplete).
bool smoothBandwidth(const double* xyz, std::size_t n, const double* raw, double radius,
  const ParallelOptions& parallel, double* out);

} // namespace gls
