// Private to the CPU multi-resolution kernel (MultiresolutionKernel.cpp, its only includer): a walk's samples packed
// once for every point of its walk region (PackedPoint, PackedCell, CellPlacements), and those inside the smallest
// scale's sphere for the whole region summed as a polynomial of p (InnerSums).
#pragma once

#include "KernelSetCalls.h"
#include "KernelVectors.h"

#include "gls/MultiresolutionKernel.h"

#include <cstring>

namespace gls
{
namespace kernel
{

/// The largest squared distance from x to a point of the region (per axis, to the farther face).
GLS_FORCE_INLINE double squaredDistanceToFarthestPoint(const WalkRegion& region, const Vec3& x)
{
  const auto farther = [](double x, double lo, double hi) GLS_INLINE_LAMBDA {
    const double below = x - lo, above = hi - x;
    const double d = below > above ? below : above;
    return d * d;
  };
  const Vec3& c = region.corner;
  const double e = region.edge;
  return farther(x.x, c.x, c.x + e) + farther(x.y, c.y, c.y + e) + farther(x.z, c.z, c.z + e);
}

/// Adds a sample to the region's InnerSums: its F (and H, or none), a = its centroid - the region's centre, M and
/// K = M^2 + V.
template <typename Set>
GLS_FORCE_INLINE void addInnerSample(
  InnerSumsT<Set>& inner, const Vec3& a, double M, double K, const double* F, const double* H)
{
  const double weights[15] = { 1.0, M, a.x, a.y, a.z, K, M * a.x, M * a.y, M * a.z, a.x * a.x, a.x * a.y, a.x * a.z,
    a.y * a.y, a.y * a.z, a.z * a.z };
  // inner.x[i] += weights[i] * X, every value of a row at a time (four-double vectors while four remain, in the
  // vector builds).
  static constexpr int V = Set::kValues; // static: the lambda below reads it without a capture (clang)
  const auto add = [&weights](double(*sums)[V], int count, const double* X) GLS_INLINE_LAMBDA {
#if GLS_KERNEL_VECTORS
    Double4 x4[V / 4];
    for (int v = 0; v < V / 4; ++v)
    {
      x4[v] = load4(X + 4 * v);
    }
#endif
    for (int i = 0; i < count; ++i)
    {
      double* row = sums[i];
      int j = 0;
#if GLS_KERNEL_VECTORS
      for (; j + 4 <= V; j += 4)
      {
        store4(row + j, load4(row + j) + weights[i] * x4[j / 4]);
      }
#endif
      for (; j < V; ++j)
      {
        row[j] += weights[i] * X[j];
      }
    }
  };
  add(inner.f, 15, F);
  if (H)
  {
    add(inner.h, 5, H);
  }
  ++inner.samples;
}

/// Adds the InnerSums' share of the first shell for p, u = p - (the region's centre): with mean = M - 2 a . u + |u|^2,
/// the sums of F, mean F + 2 H and (mean^2 + V) F + 4 mean H (wholeShare's m and c, InnerSums), expanded in u.
template <typename Set>
GLS_FORCE_INLINE void addInnerSums(const InnerSumsT<Set>& inner, const Vec3& u, AggregateMomentsT<Set>& bin)
{
  if (inner.samples == 0)
  {
    return;
  }
  const double uu = squaredNorm(u);
  const double q[6] = { u.x * u.x, 2.0 * u.x * u.y, 2.0 * u.x * u.z, u.y * u.y, 2.0 * u.y * u.z, u.z * u.z };
  constexpr int V = Set::kValues, R = AggregateMomentsT<Set>::kStride;
  for (int j = 0; j < V; ++j)
  {
    const double F = inner.f[0][j], MF = inner.f[1][j], KF = inner.f[5][j];
    const double uaF = u.x * inner.f[2][j] + u.y * inner.f[3][j] + u.z * inner.f[4][j];
    const double uMaF = u.x * inner.f[6][j] + u.y * inner.f[7][j] + u.z * inner.f[8][j];
    const double uaauF = q[0] * inner.f[9][j] + q[1] * inner.f[10][j] + q[2] * inner.f[11][j] +
      q[3] * inner.f[12][j] + q[4] * inner.f[13][j] + q[5] * inner.f[14][j];
    const double uaH = u.x * inner.h[2][j] + u.y * inner.h[3][j] + u.z * inner.h[4][j];
    const double meanF = MF - 2.0 * uaF + uu * F;
    const double meanH = inner.h[1][j] - 2.0 * uaH + uu * inner.h[0][j];
    // mean^2 = M^2 - 4 M a.u + 2 M |u|^2 + 4 (a.u)^2 - 4 (a.u) |u|^2 + |u|^4
    const double squareF = KF - 4.0 * uMaF + 2.0 * uu * MF + 4.0 * uaauF - 4.0 * uu * uaF + uu * uu * F;
    bin.m[j] += F;
    bin.m[R + j] += meanF + 2.0 * inner.h[0][j];
    bin.m[2 * R + j] += squareF + 4.0 * meanH;
  }
}

/// The samples of a walk (cells: the moment set's cell sums, cellMoments), packed once for every point of its region,
/// about an origin o near it (the corner of its far region, or its own; x = q - o): the points with their fitted values
/// f (MomentSet.h), the cells with their CellSample (direction from the region's centre), so that a point adds them as
/// they are and moves its sums from o to itself once per scale (fitAllScalesAboutOrigin) instead of forming them for
/// every sample. The samples inside the first shell's sphere for every point of the region (below sq0 = scales[0]^2) go
/// to s.inner instead (InnerSums).
template <typename Set>
GLS_FORCE_INLINE void packWalk(const MultiresolutionView& v, const typename Set::Cell* cells, const WalkRegion& region,
  const Vec3& o, double sq0, MultiresolutionScratchT<Set>& s)
{
  const Vec3 anchor = regionCentre(region);
  std::memset(static_cast<void*>(&s.inner), 0, sizeof(s.inner)); // all 0.0
  s.packedCells.resize(s.taken.size());
  s.placements.resize(s.taken.size());
  std::size_t packed = 0;
  for (std::size_t k = 0; k < s.taken.size(); ++k)
  {
    typename Set::Cell formed;
    const typename Set::Cell& cell = cellMomentsIn<Set>(v, cells, s.taken[k], s.takenLevel[k], formed);
    PackedCellT<Set>& out = s.packedCells[packed];
    const Vec3 a = cell.centroid - anchor;
    cellSampleIn(cell, o, a, out.sample);
    const double spread = out.sample.spreadPerPoint, half = out.sample.halfWidth;
    if (squaredDistanceToFarthestPoint(region, cell.centroid) + spread + half < sq0)
    {
      const double M = squaredNorm(a) + spread;
      addInnerSample(s.inner, a, M, M * M + spreadVariance(half), out.sample.sums, out.sample.gradient);
      continue;
    }
    s.placements.set(packed, cell.centroid, spread, half);
    ++packed;
  }
  s.packedCells.resize(packed);
  s.placements.resize(packed);
  std::size_t n = 0;
  for (const PointSpan& span : s.read)
  {
    n += span.last - span.first;
  }
  s.packedPoints.resize(n);
  PackedPointT<Set>* out = s.packedPoints.data();
  for (const PointSpan& span : s.read)
  {
    for (std::uint32_t i = span.first; i < span.last; ++i)
    {
      const Vec3 q = v.points.position(i);
      const Vec3 x = q - o;
      out->position = q;
      Set::pointValues(x, squaredNorm(x), v.points.normal(i), out->sums);
      if (squaredDistanceToFarthestPoint(region, q) < sq0)
      {
        const Vec3 a = q - anchor;
        const double M = squaredNorm(a);
        addInnerSample(s.inner, a, M, M * M, out->sums, nullptr);
        continue;
      }
      ++out;
    }
  }
  s.packedPoints.resize(static_cast<std::size_t>(out - s.packedPoints.data()));
}

} // namespace kernel
} // namespace gls
