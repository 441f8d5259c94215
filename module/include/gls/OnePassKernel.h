// The CPU form of the one-pass evaluation (evaluateAllScales in PointScaleSpace.h): the same binning and the same
// moment arithmetic, arranged for a CPU core. Each grid row of candidates is tested in batches without a branch per
// candidate (the ball test only advances a write index), the batch is binned by the branch-free table step, then
// added to the bins; on processors with AVX2 and FMA a build of the loop for those instructions is chosen at run
// time. Results are deterministic on a given processor (the order of the sums is the grid's); they can differ from
// evaluateAllScales in the last bits (grouping and fused multiply-adds), which the tests bound.
#pragma once

#include "gls/PointScaleSpace.h"
#include "gls/ShapeOperator.h"

namespace gls
{

/// Which build of the loop evaluateAllScalesOnCpu runs.
enum class CpuKernelBuild
{
  Fastest = 0, ///< AVX2 + FMA where the processor has them, else the portable build
  Portable = 1 ///< the build for any x86-64 (SSE2) processor, whatever this one has
};

/// Fits every scale of the evaluation point p in one pass, as evaluateAllScales. bins: S scratch moment sets; out:
/// S samples (nothing is written when there are no scales).
void evaluateAllScalesOnCpu(const GridView& g, const Vec3& p, const ScaleBinning& b, double minNeighbors,
  Moments* bins, ScaleSample* out, CpuKernelBuild build = CpuKernelBuild::Fastest);

/// evaluateAllScalesOnCpu with the principal curvatures (ShapeOperatorMoments): out, S curvature samples.
void evaluateAllScalesOnCpu(const GridView& g, const Vec3& p, const ScaleBinning& b, double minNeighbors,
  MomentsT<ShapeOperatorMoments>* bins, CurvatureSample* out, CpuKernelBuild build = CpuKernelBuild::Fastest);

/// The build of the loop evaluateAllScalesOnCpu runs on this processor: "avx2+fma" or "baseline".
const char* onePassKernelBuild();

} // namespace gls
