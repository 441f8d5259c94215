// SpatialTiles cuts a cloud into boxes of about equal point counts (the leaves of a kd split at medians), so that a
// run too large for its memory budget can take one box at a time with the points around it (TiledScaleSpace).
#pragma once

#include <cstddef>
#include <vector>

namespace gls
{

class SpatialTiles
{
public:
  /// Cuts the finite positions among the `count` points (xyz interleaved) into at most `tiles` boxes: repeatedly the
  /// box holding the most points of a regular sample (at most kSample points) is halved along the longest extent of
  /// its sample, at the sample's median. Fewer boxes come back when the points cannot be cut further (all in one
  /// position). Deterministic: the same points give the same boxes.
  static SpatialTiles plan(const double* xyz, std::size_t count, std::size_t tiles);

  /// The most points the plan samples.
  static constexpr std::size_t kSample = 1 << 17;

  std::size_t count() const { return this->Low.size(); }

  /// True when p lies in box k. The boxes are half-open ([low, high) on every axis, unbounded outside the sample),
  /// so every finite position lies in exactly one; a position with a non-finite coordinate counts as in box 0.
  bool holds(std::size_t k, const double* p) const;

  /// True when p is at most `reach` from box k along every axis (a superset of the points within distance reach).
  /// False for a position with a non-finite coordinate.
  bool near(std::size_t k, const double* p, double reach) const;

private:
  struct Corner
  {
    double v[3];
  };
  std::vector<Corner> Low, High;
};

} // namespace gls
