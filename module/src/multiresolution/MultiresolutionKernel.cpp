#include "gls/MultiresolutionKernel.h"

#include "MultiresolutionKernelBody.h"

namespace gls
{

void evaluateAllScalesMultiresolutionOnCpu(const MultiresolutionView& v, const Vec3& p, const ScaleBinning& b,
  double minNeighbors, MultiresolutionScratch& s, ScaleSample* out, CpuKernelBuild build)
{
  multiresolution::evaluateAllScalesMultiresolutionOnCpuFor<OrientedSphereMoments>(
    v, v.cells, p, b, minNeighbors, s, out, build);
}

} // namespace gls
