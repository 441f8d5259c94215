// The CPU multi-resolution kernel for the principal curvatures' moment set, in a file of its own: instantiated beside
// the oriented sphere's (MultiresolutionKernel.cpp), it changed how the compiler inlines their shared parts, and so
// where the AVX2 build fuses multiply-adds, in the sphere's samples (their last bits).
#include "gls/MultiresolutionKernel.h"

#include "MultiresolutionKernelBody.h"

namespace gls
{

void evaluateAllScalesMultiresolutionOnCpu(const MultiresolutionView& v, const CurvatureCell* cells, const Vec3& p,
  const ScaleBinning& b, double minNeighbors, MultiresolutionScratchT<ShapeOperatorMoments>& s, CurvatureSample* out,
  CpuKernelBuild build)
{
  multiresolution::evaluateAllScalesMultiresolutionOnCpuFor<ShapeOperatorMoments>(
    v, cells, p, b, minNeighbors, s, out, build);
}

} // namespace gls
