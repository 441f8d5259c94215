// Denoising by MLS projection on the CPU: every point moves onto the GLS surface of the input cloud at its own scale
// (a fixed scale, or a per-point bandwidth), see gls/Projection.h for one point.
#pragma once

#include "gls/ParallelFor.h"

#include <cstddef>

namespace gls
{

struct ProjectionSettings
{
  double minNeighbors = 6.0;   ///< fits with fewer neighbours in the ball are undefined
  int maxIterations = 50;      ///< fits per point at most
  double tolerance = 1e-6;     ///< stop when a step is at most tolerance * scale
  ParallelOptions parallel;
};

/// Outputs per point (arrays of n, or 3n for vectors). A point whose scale is not finite and positive, whose
/// coordinates are not finite, or whose fit becomes undefined keeps its input position and normal (normal
/// normalized, or NaN if it cannot be) and gets displacement NaN; its iterations are 0 when it was not projected at
/// all, else the fits made up to the undefined one.
struct ProjectionOutputs
{
  double* points;        ///< projected positions
  double* normals;       ///< eta at the projected position (unit)
  double* displacement;  ///< |projected - input| (length), NaN when not projected
  int* iterations;       ///< fits made; converged points have fewer than maxIterations or a final step <= tol
  unsigned char* converged; ///< 1 when the last step was at most tolerance * scale
};

/// points, normals: n interleaved triples (points with non-finite coordinates or zero/non-finite normals are left
/// out of every neighbourhood); scales: n per-point scales (length). Deterministic for any thread count. Returns
/// false if aborted (the outputs are then incomplete).
bool projectPointCloud(const double* points, const double* normals, std::size_t n, const double* scales,
  const ProjectionSettings& settings, const ProjectionOutputs& out);

} // namespace gls
