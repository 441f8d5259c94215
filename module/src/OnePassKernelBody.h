// Private to the one-pass CPU kernel (OnePassKernel.cpp, and the tests that run it with a moment set of their own):
// the kernel of OnePassKernel.h for any moment set (MomentSet.h), in a baseline and an AVX2 + FMA build.
#pragma once

#include "KernelBatches.h"
#include "KernelSetCalls.h"

#include "gls/OnePassKernel.h"

#include <cstring>

namespace gls
{
namespace onepass
{

#if GLS_KERNEL_VECTORS
/// addToMoments (MomentBins.h) with the values f four at a time (for the oriented sphere's eight, two vectors of
/// four): the same products and sums, element by element (fused into multiply-adds in the AVX2 build).
template <typename Set>
GLS_FORCE_INLINE void addToMomentsVectorized(MomentsT<Set>& a, const Vec3& x, double d2, const Vec3& n)
{
  constexpr int V = MomentsT<Set>::kValues, W = MomentsT<Set>::kWeighted;
  double f[Set::kValues];
  Set::pointValues(x, d2, n, f);
  const double d4 = d2 * d2;
  kernel::addTimesPowers(a.m, f, W, V, true, d2, d4);
  if (W < V)
  {
    kernel::addTimesPowers(a.m + W, f + W, V - W, V, true, d2, d4, false); // the omega-values: two powers
  }
  a.m[MomentsT<Set>::kSixthPower] += d4 * d2;
}

#else
/// Compilers without the GCC/clang vector extension add the moments with the scalar addToMoments.
template <typename Set>
GLS_FORCE_INLINE void addToMomentsVectorized(MomentsT<Set>& a, const Vec3& x, double d2, const Vec3& n)
{
  addToMoments(a, x, d2, n);
}
#endif

/// Adds the candidates [begin, end) of one grid row that lie inside the open ball of squared radius r2 around p.
template <typename Set>
GLS_FORCE_INLINE void addRun(const GridView& g, const Vec3& p, const ScaleBinning& b, double r2,
  std::uint64_t begin, std::uint64_t end, MomentsT<Set>* bins)
{
  kernel::addInsideBall(
    p, b, r2, begin, end, [](std::uint64_t c) { return c; },
    [&](std::uint64_t i) -> const Vec3& { return g.points[i]; },
    [&](std::uint64_t i, double d2, int k) { addToMomentsVectorized(bins[k], g.points[i] - p, d2, g.normals[i]); });
}

template <typename Set>
GLS_FORCE_INLINE void evaluate(const GridView& g, const Vec3& p, const ScaleBinning& shared, double minNeighbors,
  MomentsT<Set>* bins, typename Set::Sample* out)
{
  const ScaleBinning b = shared; // a local copy: the stores to the bins cannot alias it
  if (b.count <= 0)
  {
    return;
  }
  std::memset(static_cast<void*>(bins), 0, sizeof(MomentsT<Set>) * static_cast<std::size_t>(b.count)); // all 0.0
  // The rows of forEachInBall, written out: a callback passed to that template would be compiled once, for the
  // portable build, and called from the AVX2 build (measured: 39 s instead of 5.9 s on P1, one thread).
  const double r = b.scales[b.count - 1];
  if (g.count > 0 && r > 0.0)
  {
    const CellBlock block = ballCellBlock(g, p, r);
    for (std::int64_t z = block.z0; z <= block.z1; ++z)
    {
      for (std::int64_t y = block.y0; y <= block.y1; ++y)
      {
        std::uint64_t begin, end;
        if (blockRow(g, block, z, y, &begin, &end))
        {
          addRun(g, p, b, r * r, begin, end, bins);
        }
      }
    }
  }
  kernel::fitAllScalesIn(b, minNeighbors, bins, out);
}

template <typename Set>
void evaluateBaseline(const GridView& g, const Vec3& p, const ScaleBinning& b, double minNeighbors,
  MomentsT<Set>* bins, typename Set::Sample* out)
{
  evaluate(g, p, b, minNeighbors, bins, out);
}

#if GLS_KERNEL_DISPATCH
template <typename Set>
__attribute__((target("avx2,fma"))) void evaluateAvx2(const GridView& g, const Vec3& p, const ScaleBinning& b,
  double minNeighbors, MomentsT<Set>* bins, typename Set::Sample* out)
{
  evaluate(g, p, b, minNeighbors, bins, out);
}

#endif


/// evaluateAllScalesOnCpu for the moment set Set (MomentSet.h).
template <typename Set>
void evaluateAllScalesOnCpuFor(const GridView& g, const Vec3& p, const ScaleBinning& b, double minNeighbors,
  MomentsT<Set>* bins, typename Set::Sample* out, CpuKernelBuild build)
{
#if GLS_KERNEL_DISPATCH
  if (build == CpuKernelBuild::Fastest && kernel::hasAvx2())
  {
    evaluateAvx2<Set>(g, p, b, minNeighbors, bins, out);
    return;
  }
#endif
  evaluateBaseline<Set>(g, p, b, minNeighbors, bins, out);
}

} // namespace onepass
} // namespace gls
