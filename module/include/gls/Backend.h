// Compute backends of the scale-space engine and what this machine can run. The CUDA backend runs the same
// host/device per-point code (PointScaleSpace.h) as the CPU engine, on a grid the device builds itself.
#pragma once

#include "gls/GridView.h"
#include "gls/MultiresolutionView.h"
#include "gls/PointScaleSpace.h"

#include <cstddef>
#include <memory>
#include <string>

namespace gls
{

enum class Backend
{
  Auto = 0, ///< CUDA when compiled in and a working device is present, else the CPU
  CPU = 1,  ///< the multi-threaded CPU engine
  CUDA = 2  ///< the CUDA engine (falls back to the CPU, with the reason, when it cannot run)
};

const char* backendName(Backend backend);

/// Whether the CUDA backend was compiled into this build (GLS_ENABLE_CUDA).
bool cudaCompiledIn();

/// Whether CUDA can run here, checked once per process (driver, device count, a test allocation), with the reason
/// when it cannot and the device's name when it can.
struct CudaAvailability
{
  bool usable = false;
  std::string reason;
  std::string device;
};
const CudaAvailability& cudaAvailability();

/// The scale-space evaluation on a CUDA device: holds the device copy of the grid and the scale binning.
/// Every CUDA call is checked; a failure returns false with a message and leaves the object unusable.
class CudaScaleSpace
{
public:
  CudaScaleSpace();
  ~CudaScaleSpace();
  CudaScaleSpace(const CudaScaleSpace&) = delete;
  CudaScaleSpace& operator=(const CudaScaleSpace&) = delete;

  /// Uploads the grid points (with unit normals and ids) and builds the device grid by sorting them by cell with
  /// the geometry (origin, cell size, dims) of `geometry`; uploads the scales and the binning table.
  bool prepare(const GridView& geometry, const ScaleBinning& binning, double minNeighbors, std::string& error);

  /// The multi-resolution evaluation instead: uploads the pyramid as built on the host (its nodeCount nodes, its
  /// cellCount summed cells, top keys, points and normals in pyramid order), the scales and the binning table;
  /// evaluate() then runs evaluateAllScalesMultiresolutionByWindows (bitwise evaluateAllScalesMultiresolution, the
  /// host/device loop the CPU engine's kernel is tested against).
  bool prepare(const MultiresolutionView& pyramid, std::size_t nodeCount, std::size_t cellCount,
    const ScaleBinning& binning, double minNeighbors, std::string& error);

  /// How many positions one evaluate() call may take (sized from the device's free memory).
  std::size_t chunkCapacity() const;

  /// Evaluates `count` positions (count <= chunkCapacity()) at every scale; out: count x S samples, point-major.
  bool evaluate(const Vec3* positions, std::size_t count, ScaleSample* out, std::string& error);

private:
  /// Uploads the scales and binning table and sizes the chunks.
  bool prepareBinning(const ScaleBinning& binning, double minNeighbors, std::string& error);

  struct Device;
  std::unique_ptr<Device> State;
};

} // namespace gls
