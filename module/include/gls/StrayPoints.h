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
/// extent. A cloud of fewer than 100 finite points has none (too few for quantiles). Deterministic. The steps below,
/// which a distributed run takes over its pieces.
std::vector<std::uint64_t> findStrayPoints(const double* xyz, std::size_t n);

/// The robust box of a cloud (length unit); `valid` false where the cloud is too small or flat to have one (then no
/// point is stray).
struct StrayBox
{
  double low[3] = { 0.0, 0.0, 0.0 };
  double high[3] = { 0.0, 0.0, 0.0 };
  double extent = 0.0; ///< the box's largest side
  bool valid = false;
};

/// The sample's stride for a cloud of `total` points (1 up to 2^20 points): every stride-th point is sampled.
std::size_t straySampleStride(std::size_t total);

/// Appends to `sample` (3 values a point) the finite positions among every `stride`-th of the n positions of xyz.
void appendStraySample(const double* xyz, std::size_t n, std::size_t stride, std::vector<double>& sample);

/// The robust box of a sample (3 values a point; reordered), for a cloud of `finite` finite points in all.
StrayBox strayBoxOfSample(std::vector<double>& sample, std::size_t finite);

/// The indices (increasing) of the finite positions of xyz outside the box widened by its extent on every side.
std::vector<std::uint64_t> strayCandidates(const double* xyz, std::size_t n, const StrayBox& box);

/// For each candidate of `where` (3 values each: every candidate of the cloud), 1 where fewer than
/// kStrayClusterNeighbors other candidates lie within kStrayClusterRadius times the box's extent (isolated).
std::vector<unsigned char> isolatedCandidates(const std::vector<double>& where, const StrayBox& box);

} // namespace gls
