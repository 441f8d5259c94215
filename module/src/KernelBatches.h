// Private to the CPU kernels (OnePassKernel.cpp, MultiresolutionKernel.cpp): the batched ball test. Candidates are
// tested against the open ball in batches; the test only advances a write index (no branch to mispredict at the
// ball's edge), then the batch's survivors are binned, then added, each step a loop of its own.
#pragma once

#include "KernelVectors.h"

#include "gls/PointScaleSpace.h"

namespace gls
{
namespace kernel
{

constexpr int kBatch = 64;

/// For the candidates c in [begin, end), in order, each the sample id(c) at position(id(c)): calls add(id(c), d2, k)
/// for those whose squared distance d2 to p is below r2, k the first scale holding them (firstScaleHolding). Always
/// inlined, with its callbacks, into the caller's build (baseline or AVX2).
template <typename Index, typename Id, typename Position, typename Add>
GLS_FORCE_INLINE void addInsideBall(
  const Vec3& p, const ScaleBinning& b, double r2, Index begin, Index end, Id&& id, Position&& position, Add&& add)
{
  decltype(id(begin)) inside[kBatch];
  double squared[kBatch];
  int scale[kBatch];
  for (Index c = begin; c < end; c += kBatch)
  {
    const int m = static_cast<int>(end - c < kBatch ? end - c : kBatch);
    int n = 0;
    for (int j = 0; j < m; ++j)
    {
      const auto i = id(c + j);
      const double d2 = squaredNorm(position(i) - p);
      inside[n] = i;
      squared[n] = d2;
      n += d2 < r2 ? 1 : 0;
    }
    for (int j = 0; j < n; ++j)
    {
      scale[j] = firstScaleHolding(b, squared[j]);
    }
    for (int j = 0; j < n; ++j)
    {
      add(inside[j], squared[j], scale[j]);
    }
  }
}

} // namespace kernel
} // namespace gls
