// Private to the CPU kernels (OnePassKernelBody.h, src/multiresolution): how they call a moment set's fits and cell
// forms. For a set with omega-values (the principal curvatures', ShapeOperator.h) these are inlined into the kernels'
// AVX2 builds: left out of line, they ran without AVX2 and FMA (HostDevice.h), 8% of C1's multi-resolution time with
// the curvatures. The oriented sphere's stay the calls they always were, so that its kernels' object code, and with
// it every sphere sample, keeps its bits (checked with objdump -d before and after).
#pragma once

#include "gls/CellMoments.h"
#include "gls/MultiresolutionTakeWhole.h"
#include "gls/PointScaleSpace.h"

namespace gls
{
namespace kernel
{

/// Whether the kernels inline the set's fits and cell forms (a set with omega-values).
template <typename Set>
constexpr bool kInlinesSetCalls = Set::kOmegaValues > 0;

/// fitAllScalesFromBins.
template <typename Layout>
GLS_FORCE_INLINE void fitAllScalesIn(
  const ScaleBinning& b, double minNeighbors, const Layout* bins, SampleOf<Layout>* out)
{
  if constexpr (kInlinesSetCalls<typename Layout::Set>)
  {
    fitAllScalesFromBinsInlined(b, minNeighbors, bins, out);
  }
  else
  {
    fitAllScalesFromBins(b, minNeighbors, bins, out);
  }
}

/// cellMoments: the cell's sums, read where they are stored or formed into `formed`.
template <typename Set>
GLS_FORCE_INLINE const typename Set::Cell& cellMomentsIn(const MultiresolutionView& v,
  const typename Set::Cell* cells, std::uint32_t node, int level, typename Set::Cell& formed)
{
  if constexpr (kInlinesSetCalls<Set>)
  {
    return cellMomentsOf<Set>(v, cells, node, level, formed);
  }
  else
  {
    cellMoments<Set>(v, cells, node, level, formed);
    return formed;
  }
}

/// makeCellSample.
template <typename Set>
GLS_FORCE_INLINE void cellSampleIn(
  const typename Set::Cell& cell, const Vec3& origin, const Vec3& direction, CellSampleT<Set>& s)
{
  if constexpr (kInlinesSetCalls<Set>)
  {
    formCellSample(cell, origin, direction, s);
  }
  else
  {
    makeCellSample(cell, origin, direction, s);
  }
}

} // namespace kernel
} // namespace gls
