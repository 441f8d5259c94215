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
  /// The deepest chain of cuts a plan makes (a box that deep is not cut further).
  static constexpr int kMaximumDepth = 40;

  std::size_t count() const { return this->Low.size(); }

  /// True when p lies in box k. The boxes are half-open ([low, high) on every axis, unbounded outside the sample),
  /// so every finite position lies in exactly one; a position with a non-finite coordinate counts as in box 0.
  bool holds(std::size_t k, const double* p) const;

  /// The box that holds p (holds(tileOf(p), p) is true), down the cuts.
  std::size_t tileOf(const double* p) const;

  /// True when p is at most `reach` from box k along every axis (a superset of the points within distance reach).
  /// False for a position with a non-finite coordinate.
  bool near(std::size_t k, const double* p, double reach) const;

  /// Calls f(k) once for every box k that p is near (as near(k, p, reach)), in no particular order: down the cuts, so
  /// a point costs the depth of the cuts and the boxes it is near, not one test per box.
  template <typename F>
  void forEachNear(const double* p, double reach, F&& f) const;

private:
  struct Corner
  {
    double v[3];
  };
  /// A cut: the points below `split` along `axis` go to `below`, the others to `above`; a child that is a box k is
  /// written -(k + 1).
  struct Cut
  {
    int axis;
    double split;
    long below, above;
  };
  std::vector<Corner> Low, High;
  std::vector<Cut> Cuts; ///< the first is the root (none for one box)
};

template <typename F>
void SpatialTiles::forEachNear(const double* p, double reach, F&& f) const
{
  if (this->Cuts.empty())
  {
    if (this->near(0, p, reach))
    {
      f(std::size_t(0));
    }
    return;
  }
  long stack[2 * kMaximumDepth + 2];
  int top = 0;
  stack[top++] = 0;
  while (top > 0)
  {
    const long node = stack[--top];
    if (node < 0)
    {
      const std::size_t k = static_cast<std::size_t>(-node - 1);
      if (this->near(k, p, reach))
      {
        f(k);
      }
      continue;
    }
    const Cut& c = this->Cuts[static_cast<std::size_t>(node)];
    if (p[c.axis] >= c.split - reach)
    {
      stack[top++] = c.above;
    }
    if (p[c.axis] <= c.split + reach)
    {
      stack[top++] = c.below;
    }
  }
}

} // namespace gls
