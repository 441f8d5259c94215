// Stray points: returns far from everything else (birds, multipath, a mistyped line), which would stretch a cloud's
// bounding box, and with it every scale relative to its diagonal, without changing any fit near the object.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gls
{

/// The fraction of a cloud whose spread the robust box ignores on each side of each axis (its quantiles 0.01 and
/// 0.99): up to 1% of the points may be stray without moving it.
constexpr double kStrayQuantile = 0.01;

/// A stray candidate keeps its place when at least this many other candidates lie within kStrayClusterRadius of the
/// robust extent: a small object standing apart (a pole, a car) is kept, a lone return is not.
constexpr int kStrayClusterNeighbors = 3;
constexpr double kStrayClusterRadius = 0.1;

/// The indices (increasing) of the isolated points among the n finite positions of xyz (3 n values; non-finite
/// positions are neither counted nor returned): the points outside the robust box (the quantiles kStrayQuantile and
/// 1 - kStrayQuantile of every axis, of a regular sample of at most 2^20 points) widened on every side by its largest
/// extent, that have fewer than kStrayClusterNeighbors other such points within kStrayClusterRadius times that
/// extent. A cloud of fewer than 100 finite points has none (too few for quantiles). Deterministic.
std::vector<std::uint64_t> findStrayPoints(const double* xyz, std::size_t n);

} // namespace gls
