// Private to the CPU multi-resolution kernel (MultiresolutionKernel.cpp, its only includer): how a packed sample is
// added to the bin of a shell, a point's fitted values at its squared distance or a cell's share of the shell.
#pragma once

#include "KernelVectors.h"

#include "gls/AggregateMoments.h"
#include "gls/CellMoments.h"

namespace gls
{
namespace kernel
{

/// Adds the values f of a point at squared distance d2 (addSampleSums in AggregateMoments.h: the same products and
/// sums, element by element, fused into multiply-adds in the AVX2 build).
GLS_FORCE_INLINE void addPackedSums(AggregateMoments& a, const double* f, double d2)
{
#if GLS_KERNEL_VECTORS
  addTimesPowers(a.m, f, kFitValues, kFitValues, false, d2, d2 * d2);
#else
  addSampleSums(a, f, d2);
#endif
}

#if GLS_KERNEL_VECTORS
/// A cell's F and H as the shell adds read them, loaded once for all the shells the cell meets: four values at a
/// time while four remain, the rest one by one.
struct LoadedSample
{
  static constexpr int kVectors = kFitValues / 4, kRest = kFitValues % 4;
  Double4 f[kVectors], g[kVectors];
  double fRest[kRest > 0 ? kRest : 1], gRest[kRest > 0 ? kRest : 1];
};

GLS_FORCE_INLINE LoadedSample loadSample(const CellSample& s)
{
  LoadedSample l;
  for (int v = 0; v < LoadedSample::kVectors; ++v)
  {
    l.f[v] = load4(s.sums + 4 * v);
    l.g[v] = load4(s.gradient + 4 * v);
  }
  for (int r = 0; r < LoadedSample::kRest; ++r)
  {
    l.fRest[r] = s.sums[4 * LoadedSample::kVectors + r];
    l.gRest[r] = s.gradient[4 * LoadedSample::kVectors + r];
  }
  return l;
}

/// A cell's share of one shell (addCellShare in CellMoments.h, the same products and sums element by element).
GLS_FORCE_INLINE void addPackedCellShare(AggregateMoments& a, const LoadedSample& f, const ShellShare& share)
{
  double* m = a.m;
  for (int j = 0; j < 3; ++j)
  {
    const double mj = share.m[j], cj = share.c[j];
    double* row = m + j * kFitValues;
    for (int v = 0; v < LoadedSample::kVectors; ++v)
    {
      store4(row + 4 * v, load4(row + 4 * v) + (mj * f.f[v] + cj * f.g[v]));
    }
    for (int r = 0; r < LoadedSample::kRest; ++r)
    {
      row[4 * LoadedSample::kVectors + r] += mj * f.fRest[r] + cj * f.gRest[r];
    }
  }
}
#endif

GLS_FORCE_INLINE void addPackedCellShare(AggregateMoments& a, const CellSample& s, const ShellShare& share)
{
#if GLS_KERNEL_VECTORS
  addPackedCellShare(a, loadSample(s), share);
#else
  addCellShare(a, s, share);
#endif
}

} // namespace kernel
} // namespace gls
