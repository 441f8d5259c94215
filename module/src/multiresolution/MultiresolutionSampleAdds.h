// Private to the CPU multi-resolution kernel (MultiresolutionKernel.cpp, its only includer): how a packed sample is
// added to the bin of a shell, a point's nine sums at its squared distance or a cell's share of the shell.
#pragma once

#include "KernelVectors.h"

#include "gls/AggregateMoments.h"
#include "gls/CellMoments.h"

namespace gls
{
namespace kernel
{

/// Adds the sums f = (f0, f1, f8) of a point at squared distance d2 (addSampleSums in AggregateMoments.h: the same
/// products and sums, element by element, fused into multiply-adds in the AVX2 build).
GLS_FORCE_INLINE void addPackedSums(AggregateMoments& a, const double* f, double d2)
{
#if GLS_KERNEL_VECTORS
  const Double4 f0 = load4(f);
  const Double4 f1 = load4(f + 4);
  const double f8 = f[8];
  const double d4 = d2 * d2;
  double* m = a.m;
  store4(m, load4(m) + f0);
  store4(m + 4, load4(m + 4) + f1);
  m[8] += f8;
  store4(m + 9, load4(m + 9) + d2 * f0);
  store4(m + 13, load4(m + 13) + d2 * f1);
  m[17] += d2 * f8;
  store4(m + 18, load4(m + 18) + d4 * f0);
  store4(m + 22, load4(m + 22) + d4 * f1);
  m[26] += d4 * f8;
#else
  addSampleSums(a, f, d2);
#endif
}

#if GLS_KERNEL_VECTORS
/// A cell's F and H as the shell adds read them, loaded once for all the shells the cell meets.
struct LoadedSample
{
  Double4 f0, f1, g0, g1;
  double f8, g8;
};

GLS_FORCE_INLINE LoadedSample loadSample(const CellSample& s)
{
  return { load4(s.sums), load4(s.sums + 4), load4(s.gradient), load4(s.gradient + 4), s.sums[8], s.gradient[8] };
}

/// A cell's share of one shell (addCellShare in CellMoments.h, the same products and sums element by element).
GLS_FORCE_INLINE void addPackedCellShare(AggregateMoments& a, const LoadedSample& f, const ShellShare& share)
{
  double* m = a.m;
  for (int j = 0; j < 3; ++j)
  {
    const double mj = share.m[j], cj = share.c[j];
    double* row = m + j * kAggregateValues;
    store4(row, load4(row) + (mj * f.f0 + cj * f.g0));
    store4(row + 4, load4(row + 4) + (mj * f.f1 + cj * f.g1));
    row[8] += mj * f.f8 + cj * f.g8;
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
