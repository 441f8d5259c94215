// How the moments of each ball are evaluated (docs/math.md, "Multi-resolution evaluation"): exactly, every point of
// the ball (the one pass), or at a resolution that follows the distance from the evaluation point. And the rule
// that chooses between them (Auto): exact while the largest ball holds on average at most about 5,000 points.
#pragma once

#include <cstddef>

namespace gls
{

enum class Evaluation
{
  Exact = 0,          ///< every point of every ball (bit for bit the one pass)
  Multiresolution = 1 ///< cells of edge <= Accuracy * distance taken whole (MultiresolutionTakeWhole.h)
};

/// How the exact evaluation fits: the method of reference, or the one pass that every evaluation is tested against it.
enum class EvaluationMethod
{
  OnePass,   ///< all scales from one gather (the moment formulation); the default
  PerScale   ///< one ball query and one weighted fit per scale (reference and benchmark baseline; CPU only)
};

/// The default Accuracy (epsilon) of the multi-resolution evaluation (docs/math.md gives the measurements).
constexpr double kDefaultAccuracy = 0.5;

/// Auto stays exact while the largest ball holds on average at most this many points.
constexpr double kExactNeighborLimit = 5000.0;

/// A deterministic estimate of the mean number of points within a radius of the evaluated points: up to 256
/// evaluation points (an even stride over the first `evaluated` points) against up to 20,000 neighbours (an even
/// stride over all `count` points), scaled by count / neighbours. Exact counts when count <= 20,000. Points with a
/// non-finite coordinate are skipped. The sums can be added over distributed pieces before taking the mean.
struct BallCountEstimate
{
  double neighbors = 0.0; ///< the estimated neighbours of the sampled evaluation points, summed
  double samples = 0.0;   ///< the number of sampled evaluation points
  double mean() const { return samples > 0.0 ? neighbors / samples : 0.0; }
};

BallCountEstimate estimateBallCount(const double* xyz, std::size_t count, std::size_t evaluated, double radius);

} // namespace gls
