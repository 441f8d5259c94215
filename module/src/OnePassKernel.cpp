#include "gls/OnePassKernel.h"

#include "KernelBatches.h"

#include <cstring>

namespace gls
{
namespace
{

#if GLS_KERNEL_VECTORS
using kernel::Double4;
using kernel::load4;
using kernel::store4;

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

/// addToMoments (MomentBins.h) with the values f four at a time (for the oriented sphere's eight, two vectors of
/// four): the same products and sums, element by element (fused into multiply-adds in the AVX2 build).
GLS_FORCE_INLINE void addToMomentsVectorized(Moments& a, const Vec3& x, double d2, const Vec3& n)
{
  double f[kFitValues];
  pointValues(x, d2, n, f);
  const double d4 = d2 * d2;
  kernel::addTimesPowers(a.m, f, kMomentValues, kMomentValues, true, d2, d4);
  a.m[3 * kMomentValues] += d4 * d2;
}

#pragma GCC diagnostic pop

#else
/// Compilers without the GCC/clang vector extension add the moments with the scalar addToMoments.
GLS_FORCE_INLINE void addToMomentsVectorized(Moments& a, const Vec3& x, double d2, const Vec3& n)
{
  addToMoments(a, x, d2, n);
}
#endif

/// Adds the candidates [begin, end) of one grid row that lie inside the open ball of squared radius r2 around p.
GLS_FORCE_INLINE void addRun(const GridView& g, const Vec3& p, const ScaleBinning& b, double r2,
  std::uint64_t begin, std::uint64_t end, Moments* bins)
{
  kernel::addInsideBall(
    p, b, r2, begin, end, [](std::uint64_t c) { return c; },
    [&](std::uint64_t i) -> const Vec3& { return g.points[i]; },
    [&](std::uint64_t i, double d2, int k) { addToMomentsVectorized(bins[k], g.points[i] - p, d2, g.normals[i]); });
}

GLS_FORCE_INLINE void evaluate(
  const GridView& g, const Vec3& p, const ScaleBinning& shared, double minNeighbors, Moments* bins, ScaleSample* out)
{
  const ScaleBinning b = shared; // a local copy: the stores to the bins cannot alias it
  if (b.count <= 0)
  {
    return;
  }
  std::memset(static_cast<void*>(bins), 0, sizeof(Moments) * static_cast<std::size_t>(b.count)); // all 0.0
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
  fitAllScalesFromBins(b, minNeighbors, bins, out);
}

void evaluateBaseline(
  const GridView& g, const Vec3& p, const ScaleBinning& b, double minNeighbors, Moments* bins, ScaleSample* out)
{
  evaluate(g, p, b, minNeighbors, bins, out);
}

#if GLS_KERNEL_DISPATCH
__attribute__((target("avx2,fma"))) void evaluateAvx2(
  const GridView& g, const Vec3& p, const ScaleBinning& b, double minNeighbors, Moments* bins, ScaleSample* out)
{
  evaluate(g, p, b, minNeighbors, bins, out);
}

#endif

} // namespace

void evaluateAllScalesOnCpu(const GridView& g, const Vec3& p, const ScaleBinning& b, double minNeighbors,
  Moments* bins, ScaleSample* out, CpuKernelBuild build)
{
#if GLS_KERNEL_DISPATCH
  if (build == CpuKernelBuild::Fastest && kernel::hasAvx2())
  {
    evaluateAvx2(g, p, b, minNeighbors, bins, out);
    return;
  }
#endif
  evaluateBaseline(g, p, b, minNeighbors, bins, out);
}

const char* onePassKernelBuild()
{
#if GLS_KERNEL_DISPATCH
  if (kernel::hasAvx2())
  {
    return "avx2+fma";
  }
#endif
  return "baseline";
}

} // namespace gls
