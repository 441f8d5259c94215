#include "gls/Backend.h"

namespace gls
{

const char* backendName(Backend backend)
{
  switch (backend)
  {
    case Backend::Auto:
      return "Auto";
    case Backend::CPU:
      return "CPU";
    case Backend::CUDA:
      return "CUDA";
  }
  return "?";
}

#ifndef GLS_WITH_CUDA
// Built without CUDA: the CUDA backend reports why it cannot run.
namespace
{
const char* const kNotBuilt = "this build has no CUDA support (configured with GLS_ENABLE_CUDA=OFF)";
}

bool cudaCompiledIn()
{
  return false;
}

const CudaAvailability& cudaAvailability()
{
  static const CudaAvailability none{ false, kNotBuilt, "" };
  return none;
}

struct CudaScaleSpace::Device
{
};

CudaScaleSpace::CudaScaleSpace() = default;
CudaScaleSpace::~CudaScaleSpace() = default;

bool CudaScaleSpace::prepare(const GridView&, const ScaleBinning&, double, std::string& error)
{
  error = kNotBuilt;
  return false;
}

bool CudaScaleSpace::prepare(
  const MultiresolutionView&, std::size_t, std::size_t, const ScaleBinning&, double, std::string& error)
{
  error = kNotBuilt;
  return false;
}

bool CudaScaleSpace::prepareBinning(const ScaleBinning&, double, std::string& error)
{
  error = kNotBuilt;
  return false;
}

std::size_t CudaScaleSpace::chunkCapacity() const
{
  return 0;
}

bool CudaScaleSpace::evaluate(const Vec3*, std::size_t, ScaleSample*, std::string& error)
{
  error = kNotBuilt;
  return false;
}
#endif

} // namespace gls
