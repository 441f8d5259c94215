#include "gls/OnePassKernel.h"

#include "OnePassKernelBody.h"

namespace gls
{

void evaluateAllScalesOnCpu(const GridView& g, const Vec3& p, const ScaleBinning& b, double minNeighbors,
  Moments* bins, ScaleSample* out, CpuKernelBuild build)
{
  onepass::evaluateAllScalesOnCpuFor<OrientedSphereMoments>(g, p, b, minNeighbors, bins, out, build);
}

void evaluateAllScalesOnCpu(const GridView& g, const Vec3& p, const ScaleBinning& b, double minNeighbors,
  MomentsT<ShapeOperatorMoments>* bins, CurvatureSample* out, CpuKernelBuild build)
{
  onepass::evaluateAllScalesOnCpuFor<ShapeOperatorMoments>(g, p, b, minNeighbors, bins, out, build);
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
