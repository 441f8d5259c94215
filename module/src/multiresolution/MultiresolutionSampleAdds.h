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
template <typename Set>
GLS_FORCE_INLINE void addPackedSums(AggregateMomentsT<Set>& a, const double* f, double d2)
{
#if GLS_KERNEL_VECTORS
  if constexpr (Set::kOmegaValues == 0)
  {
    addTimesPowers(a.m, f, Set::kValues, Set::kValues, false, d2, d2 * d2);
  }
  else
  {
    // The omega-values' third moment is never read (weightedValues): their two powers only, then |x|^2's three.
    constexpr int V = Set::kValues, W = AggregateMomentsT<Set>::kWeighted, R = AggregateMomentsT<Set>::kStride;
    const double d4 = d2 * d2;
    addTimesPowers(a.m, f, W, R, false, d2, d4);
    addTimesPowers(a.m + W, f + W, V - 1 - W, R, false, d2, d4, false);
    addTimesPowers(a.m + V - 1, f + V - 1, 1, R, false, d2, d4);
  }
#else
  addSampleSums(a, f, d2);
#endif
}

#if GLS_KERNEL_VECTORS
/// A cell's F and H as the shell adds read them, loaded once for all the shells the cell meets: four values at a
/// time while four remain, the rest one by one.
template <typename Set>
struct LoadedSampleT
{
  static constexpr int kVectors = CellSampleT<Set>::kStride / 4, kRest = CellSampleT<Set>::kStride % 4;
  Double4 f[kVectors], g[kVectors];
  double fRest[kRest > 0 ? kRest : 1], gRest[kRest > 0 ? kRest : 1];
};

template <typename Set>
GLS_FORCE_INLINE LoadedSampleT<Set> loadSample(const CellSampleT<Set>& s)
{
  using LoadedSample = LoadedSampleT<Set>;
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

/// Whether the values [first, first + count) of the set are all omega-values, whose third moment is never read
/// (weightedValues): the cell shares leave it out.
template <typename Set>
constexpr bool onlyOmegaValues(int first, int count)
{
  constexpr int W = AggregateMomentsT<Set>::kWeighted;
  return first >= W && first + count <= W + Set::kOmegaValues;
}

/// A cell's share of one shell (addCellShare in CellMoments.h, the same products and sums element by element; a set
/// with omega-values leaves their third moment out).
template <typename Set>
GLS_FORCE_INLINE void addPackedCellShare(
  AggregateMomentsT<Set>& a, const LoadedSampleT<Set>& f, const ShellShare& share)
{
  using LoadedSample = LoadedSampleT<Set>;
  double* m = a.m;
  for (int j = 0; j < 3; ++j)
  {
    const double mj = share.m[j], cj = share.c[j];
    double* row = m + j * AggregateMomentsT<Set>::kStride;
    if constexpr (Set::kOmegaValues == 0)
    {
      for (int v = 0; v < LoadedSample::kVectors; ++v)
      {
        store4(row + 4 * v, load4(row + 4 * v) + (mj * f.f[v] + cj * f.g[v]));
      }
      for (int r = 0; r < LoadedSample::kRest; ++r)
      {
        row[4 * LoadedSample::kVectors + r] += mj * f.fRest[r] + cj * f.gRest[r];
      }
    }
    else
    {
      for (int v = 0; v < LoadedSample::kVectors; ++v)
      {
        if (j < 2 || !onlyOmegaValues<Set>(4 * v, 4))
        {
          store4(row + 4 * v, load4(row + 4 * v) + (mj * f.f[v] + cj * f.g[v]));
        }
      }
      for (int r = 0; r < LoadedSample::kRest; ++r)
      {
        if (j < 2 || !onlyOmegaValues<Set>(4 * LoadedSample::kVectors + r, 1))
        {
          row[4 * LoadedSample::kVectors + r] += mj * f.fRest[r] + cj * f.gRest[r];
        }
      }
    }
  }
}
#endif

template <typename Set>
GLS_FORCE_INLINE void addPackedCellShare(AggregateMomentsT<Set>& a, const CellSampleT<Set>& s, const ShellShare& share)
{
#if GLS_KERNEL_VECTORS
  addPackedCellShare(a, loadSample(s), share);
#else
  addCellShare(a, s, share);
#endif
}

} // namespace kernel
} // namespace gls
