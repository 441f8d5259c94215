// Private to the CPU multi-resolution kernel (MultiresolutionKernel.cpp, its only includer): the linearized far cells
// (docs/math.md, "Linearized far cells"), summed once per far region (LinearizedBins) and moved to each point.
#pragma once

#include "KernelSetCalls.h"
#include "KernelVectors.h"

#include "gls/MultiresolutionKernel.h"

#include <algorithm>
#include <cstring>
#include <vector>

namespace gls
{
namespace kernel
{

/// sum += c * x over every moment.
template <typename Set>
GLS_FORCE_INLINE void addScaled(AggregateMomentsT<Set>& sum, double c, const AggregateMomentsT<Set>& x)
{
  for (int j = 0; j < 3 * AggregateMomentsT<Set>::kStride; ++j)
  {
    sum.m[j] += c * x.m[j];
  }
}

/// Adds a linearized cell (FarRule) to its far region's LinearizedBins: its shares expanded at the region's centre
/// (mean |a|^2 + its spread per point, a = c - the centre), its sample about the region's corner o.
template <typename Set>
GLS_FORCE_INLINE void addLinearizedCell(const ScaleBinning& b, double r2, const typename Set::Cell& cell,
  const Vec3& o, const Vec3& a, LinearizedBinsT<Set>& far)
{
  CellSampleT<Set> sample;
  cellSampleIn(cell, o, a, sample);
  const double aa[6] = { a.x * a.x, a.x * a.y, a.x * a.z, a.y * a.y, a.y * a.z, a.z * a.z };
  forEachShellOfSpreadExpanded(
    b, r2, squaredNorm(a) + sample.spreadPerPoint, sample.halfWidth,
    [&](int k, const ShellShareExpansion& e) GLS_INLINE_LAMBDA {
      const std::size_t shell = static_cast<std::size_t>(k);
      far.firstShell = std::min(far.firstShell, k);
      addCellShare(far.value[shell], sample, e.value);
      AggregateMomentsT<Set> slope, curvature;
      clearMoments(slope);
      clearMoments(curvature);
      addCellShare(slope, sample, e.slope);
      addCellShare(curvature, sample, e.curvature);
      addMoments(far.slope[shell], slope);
      addScaled(far.slopeA[0][shell], a.x, slope);
      addScaled(far.slopeA[1][shell], a.y, slope);
      addScaled(far.slopeA[2][shell], a.z, slope);
      for (int i = 0; i < 6; ++i)
      {
        addScaled(far.curvatureAA[i][shell], aa[i], curvature);
      }
    });
}

/// The LinearizedBins of the far region F of far part `part` from the cells of its far walk (s.taken, s.takenLevel),
/// their sums about o (cells: the moment set's cell sums, cellMoments); the cells too narrow to linearize go to
/// s.farSampled[part] instead. Inlined into each build of the kernel (its loops vectorized there).
template <typename Set>
GLS_FORCE_INLINE void packFarWalk(const MultiresolutionView& v, const typename Set::Cell* cells, const WalkRegion& F,
  int part, const Vec3& o, const ScaleBinning& b, double r2, MultiresolutionWalkScratch& s, LinearizedBinsT<Set>& far)
{
  const std::size_t S = static_cast<std::size_t>(b.count);
  std::vector<AggregateMomentsT<Set>>* sets[] = { &far.value, &far.slope, &far.slopeA[0], &far.slopeA[1],
    &far.slopeA[2], &far.curvatureAA[0], &far.curvatureAA[1], &far.curvatureAA[2], &far.curvatureAA[3],
    &far.curvatureAA[4], &far.curvatureAA[5] };
  for (std::vector<AggregateMomentsT<Set>>* bins : sets)
  {
    bins->resize(S);
    std::memset(static_cast<void*>(bins->data()), 0, sizeof(AggregateMomentsT<Set>) * S); // all 0.0
  }
  far.cells = 0;
  far.firstShell = b.count;
  std::vector<std::uint32_t>& sampled = s.farSampled[part];
  std::vector<int>& sampledLevel = s.farSampledLevel[part];
  sampled.clear();
  sampledLevel.clear();
  const Vec3 centre = regionCentre(F);
  for (std::size_t k = 0; k < s.taken.size(); ++k)
  {
    typename Set::Cell formed;
    const typename Set::Cell& cell = cellMomentsIn<Set>(v, cells, s.taken[k], s.takenLevel[k], formed);
    const Vec3 a = cell.centroid - centre;
    if (linearizable(spreadHalfWidth(cell, a), a, F))
    {
      addLinearizedCell<Set>(b, r2, cell, o, a, far);
      ++far.cells;
    }
    else
    {
      sampled.push_back(s.taken[k]);
      sampledLevel.push_back(s.takenLevel[k]);
    }
  }
}

/// Adds a far region's linearized cells for p, u = p - (the region's centre) (LinearizedBins), from the first shell
/// they reach.
template <typename Set>
GLS_FORCE_INLINE void addLinearizedCells(
  const LinearizedBinsT<Set>& far, const Vec3& u, int count, AggregateMomentsT<Set>* bins)
{
  if (far.cells == 0)
  {
    return;
  }
  const double uu = squaredNorm(u);
  const double ux = -2.0 * u.x, uy = -2.0 * u.y, uz = -2.0 * u.z;
  // 2 u^T C u over the symmetric pairs: the diagonal twice, the off-diagonal four times.
  const double q[6] = { 2.0 * u.x * u.x, 4.0 * u.x * u.y, 4.0 * u.x * u.z, 2.0 * u.y * u.y, 4.0 * u.y * u.z,
    2.0 * u.z * u.z };
  for (std::size_t k = static_cast<std::size_t>(far.firstShell); k < static_cast<std::size_t>(count); ++k)
  {
    const double* value = far.value[k].m;
    const double* one = far.slope[k].m;
    const double* x = far.slopeA[0][k].m;
    const double* y = far.slopeA[1][k].m;
    const double* z = far.slopeA[2][k].m;
    const double* c[6] = { far.curvatureAA[0][k].m, far.curvatureAA[1][k].m, far.curvatureAA[2][k].m,
      far.curvatureAA[3][k].m, far.curvatureAA[4][k].m, far.curvatureAA[5][k].m };
    double* m = bins[k].m;
    // The moved sum of moment j, element by element (load reads a moment, or four from j, of a set).
    const auto moved = [&](auto load) GLS_INLINE_LAMBDA {
      const auto second = q[0] * load(c[0]) + q[1] * load(c[1]) + q[2] * load(c[2]) + q[3] * load(c[3]) +
        q[4] * load(c[4]) + q[5] * load(c[5]);
      return load(value) + (uu * load(one) + (ux * load(x) + uy * load(y) + uz * load(z))) + second;
    };
    int j = 0;
#if GLS_KERNEL_VECTORS
    for (; j + 4 <= 3 * AggregateMomentsT<Set>::kStride; j += 4)
    {
      const auto four = [j](const double* set) GLS_INLINE_LAMBDA { return load4(set + j); };
      store4(m + j, load4(m + j) + moved(four));
    }
#endif
    for (; j < 3 * AggregateMomentsT<Set>::kStride; ++j)
    {
      m[j] += moved([j](const double* set) GLS_INLINE_LAMBDA { return set[j]; });
    }
  }
}

} // namespace kernel
} // namespace gls
