// The CUDA backend: the device sorts the grid points by cell (thrust), then one thread per evaluation point runs
// evaluateAllScalesByWindows (or its multi-resolution form) in double precision: the host/device loop, bitwise
// equal to evaluateAllScales, whose binning, moment sums and fits the CPU kernel (OnePassKernel.h) shares, and which
// the core tests run on the host against it. Inputs larger than the device's free memory allows are processed in
// chunks. Every CUDA call is checked and turned into an error message.
#include "gls/Backend.h"
#include "gls/MultiresolutionReferenceWalk.h"

#include <cuda_runtime.h>
#include <thrust/binary_search.h>
#include <thrust/execution_policy.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/sort.h>
#include <thrust/system_error.h>

#include <algorithm>
#include <sstream>
#include <vector>

namespace gls
{
namespace
{

/// Records the first failing CUDA call in `error`.
bool check(cudaError_t status, const char* what, std::string& error)
{
  if (status == cudaSuccess)
  {
    return true;
  }
  std::ostringstream msg;
  msg << what << ": " << cudaGetErrorString(status) << " (" << cudaGetErrorName(status) << ")";
  error = msg.str();
  cudaGetLastError(); // clear a non-sticky error
  return false;
}

/// A device allocation freed on destruction.
template <typename T>
class DeviceArray
{
public:
  DeviceArray() = default;
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  ~DeviceArray() { this->release(); }
  bool allocate(std::size_t n, std::string& error)
  {
    this->release();
    this->Count = n;
    return check(cudaMalloc(reinterpret_cast<void**>(&this->Data), std::max<std::size_t>(n, 1) * sizeof(T)),
      "cudaMalloc", error);
  }
  bool upload(const T* host, std::size_t n, std::string& error)
  {
    return this->allocate(n, error) &&
      check(cudaMemcpy(this->Data, host, n * sizeof(T), cudaMemcpyHostToDevice), "cudaMemcpy to device", error);
  }
  void release()
  {
    if (this->Data)
    {
      cudaFree(this->Data);
      this->Data = nullptr;
    }
  }
  T* get() const { return this->Data; }

private:
  T* Data = nullptr;
  std::size_t Count = 0;
};

__global__ void cellKeysKernel(const Vec3* points, std::uint64_t n, GridView geometry, std::uint64_t* keys,
  std::uint64_t* order)
{
  const std::uint64_t i = blockIdx.x * static_cast<std::uint64_t>(blockDim.x) + threadIdx.x;
  if (i >= n)
  {
    return;
  }
  const Vec3 p = points[i];
  const std::int64_t cx = gridCellOf(geometry, p.x, 0);
  const std::int64_t cy = gridCellOf(geometry, p.y, 1);
  const std::int64_t cz = gridCellOf(geometry, p.z, 2);
  keys[i] = static_cast<std::uint64_t>((cz * geometry.dims[1] + cy) * geometry.dims[0] + cx);
  order[i] = i;
}

__global__ void gatherKernel(const std::uint64_t* order, std::uint64_t n, const Vec3* points, const Vec3* normals,
  const std::uint64_t* ids, Vec3* sortedPoints, Vec3* sortedNormals, std::uint64_t* sortedIds)
{
  const std::uint64_t i = blockIdx.x * static_cast<std::uint64_t>(blockDim.x) + threadIdx.x;
  if (i >= n)
  {
    return;
  }
  const std::uint64_t from = order[i];
  sortedPoints[i] = points[from];
  sortedNormals[i] = normals[from];
  sortedIds[i] = ids[from];
}

/// The position of evaluation i; false, with its S samples invalid, when a coordinate is not finite.
__device__ bool evaluationPoint(const Vec3* positions, std::uint64_t i, int S, ScaleSample* out, Vec3& p)
{
  p = positions[i];
  if (isFinite(p.x) && isFinite(p.y) && isFinite(p.z))
  {
    return true;
  }
  for (int k = 0; k < S; ++k)
  {
    out[i * S + k] = invalidSample<double>(0.0);
  }
  return false;
}

template <int G>
__global__ void evaluateByWindowsKernel(GridView grid, ScaleBinning binning, double minNeighbors,
  const Vec3* positions, std::uint64_t count, ScaleSample* out)
{
  const std::uint64_t i = blockIdx.x * static_cast<std::uint64_t>(blockDim.x) + threadIdx.x;
  const int S = binning.count;
  Vec3 p;
  if (i >= count || !evaluationPoint(positions, i, S, out, p))
  {
    return;
  }
  evaluateAllScalesByWindows<G>(grid, p, binning, minNeighbors, out + i * S);
}

template <int G>
__global__ void evaluateMultiresolutionByWindowsKernel(MultiresolutionView pyramid, ScaleBinning binning,
  double minNeighbors, const Vec3* positions, std::uint64_t count, ScaleSample* out)
{
  const std::uint64_t i = blockIdx.x * static_cast<std::uint64_t>(blockDim.x) + threadIdx.x;
  const int S = binning.count;
  Vec3 p;
  if (i >= count || !evaluationPoint(positions, i, S, out, p))
  {
    return;
  }
  evaluateAllScalesMultiresolutionByWindows<G>(pyramid, p, binning, minNeighbors, out + i * S);
}

/// Scales per window of the device loops (evaluateAllScalesByWindows, evaluateAllScalesMultiresolutionByWindows).
/// Measured on an H200 (docs/performance.md, "Backends: CPU and CUDA"; bunny, 20 scales, fused features), against
/// S bins per thread in global memory: exact 1M points 2.5 s (4 scales per window), 3.0 s (3), 3.2 s (2), 4.2 s (1),
/// 10.7 s (bins in memory); multi-resolution 10M points 12.7 s (4), 14.0 s (2), 17.6 s (1), 15.5 s (bins in memory).
constexpr int kScalesPerWindow = 4;

unsigned blocksFor(std::uint64_t n, unsigned threads)
{
  return static_cast<unsigned>((n + threads - 1) / threads);
}

} // namespace

bool cudaCompiledIn()
{
  return true;
}

const CudaAvailability& cudaAvailability()
{
  static const CudaAvailability probe = [] {
    CudaAvailability a;
    int count = 0;
    std::string error;
    if (!check(cudaGetDeviceCount(&count), "cudaGetDeviceCount", error))
    {
      a.reason = "no usable CUDA device: " + error;
      return a;
    }
    if (count == 0)
    {
      a.reason = "no CUDA device present";
      return a;
    }
    cudaDeviceProp prop{};
    if (!check(cudaGetDeviceProperties(&prop, 0), "cudaGetDeviceProperties", error))
    {
      a.reason = "no usable CUDA device: " + error;
      return a;
    }
    void* test = nullptr;
    if (!check(cudaMalloc(&test, 1 << 20), "test allocation", error))
    {
      a.reason = "CUDA device unusable: " + error;
      return a;
    }
    cudaFree(test);
    a.usable = true;
    a.device = prop.name;
    return a;
  }();
  return probe;
}

struct CudaScaleSpace::Device
{
  GridView Grid;
  ScaleBinning Binning;
  double MinNeighbors = 6.0;
  std::size_t Capacity = 0;
  DeviceArray<Vec3> Points, Normals;
  DeviceArray<std::uint64_t> Ids, CellStart;
  DeviceArray<double> Scales, SquaredScales;
  DeviceArray<BinningCell> Table;
  DeviceArray<Vec3> Positions;
  DeviceArray<ScaleSample> Out;
  // The multi-resolution evaluation (Multiresolution true): the pyramid.
  bool Multiresolution = false;
  MultiresolutionView Pyramid;
  DeviceArray<PyramidNode> Nodes;
  DeviceArray<PyramidCell> Cells;
  DeviceArray<std::uint64_t> TopKeys;
  DeviceArray<float> Points32, Normals32; // the pyramid's points in floats, where the host stores them so
};

/// Chunk size: half the free memory for positions and samples (the kernels keep their moments in registers).
bool CudaScaleSpace::prepareBinning(const ScaleBinning& binning, double minNeighbors, std::string& error)
{
  Device& d = *this->State;
  const int S = binning.count;
  if (!d.Scales.upload(binning.scales, S, error) || !d.SquaredScales.upload(binning.squaredScales, S, error) ||
    !d.Table.upload(binning.table, binning.tableSize, error))
  {
    return false;
  }
  d.Binning = binning;
  d.Binning.scales = d.Scales.get();
  d.Binning.squaredScales = d.SquaredScales.get();
  d.Binning.table = d.Table.get();
  d.MinNeighbors = minNeighbors;
  std::size_t freeBytes = 0, totalBytes = 0;
  if (!check(cudaMemGetInfo(&freeBytes, &totalBytes), "cudaMemGetInfo", error))
  {
    return false;
  }
  const std::size_t perPoint = sizeof(Vec3) + static_cast<std::size_t>(S) * sizeof(ScaleSample);
  d.Capacity = std::max<std::size_t>(1, std::min<std::size_t>(freeBytes / 2 / perPoint, std::size_t(1) << 22));
  return d.Positions.allocate(d.Capacity, error) && d.Out.allocate(d.Capacity * S, error);
}

CudaScaleSpace::CudaScaleSpace() = default;
CudaScaleSpace::~CudaScaleSpace() = default;

bool CudaScaleSpace::prepare(
  const GridView& geometry, const ScaleBinning& binning, double minNeighbors, std::string& error)
{
  this->State = std::make_unique<Device>();
  Device& d = *this->State;
  const std::uint64_t n = geometry.count;
  const std::size_t cells = static_cast<std::size_t>(geometry.dims[0] * geometry.dims[1] * geometry.dims[2]);
  try
  {
    // Unsorted inputs, cell keys, a stable sort by cell, then the sorted copies and the cell offsets.
    DeviceArray<Vec3> points, normals;
    DeviceArray<std::uint64_t> ids, keys, order;
    if (!points.upload(geometry.points, n, error) || !normals.upload(geometry.normals, n, error) ||
      !ids.upload(geometry.ids, n, error) || !keys.allocate(n, error) || !order.allocate(n, error))
    {
      return false;
    }
    const unsigned threads = 256;
    if (n > 0)
    {
      cellKeysKernel<<<blocksFor(n, threads), threads>>>(points.get(), n, geometry, keys.get(), order.get());
      if (!check(cudaGetLastError(), "cell key kernel", error))
      {
        return false;
      }
      thrust::stable_sort_by_key(thrust::device, keys.get(), keys.get() + n, order.get());
    }
    if (!d.Points.allocate(n, error) || !d.Normals.allocate(n, error) || !d.Ids.allocate(n, error) ||
      !d.CellStart.allocate(cells + 1, error))
    {
      return false;
    }
    if (n > 0)
    {
      gatherKernel<<<blocksFor(n, threads), threads>>>(order.get(), n, points.get(), normals.get(), ids.get(),
        d.Points.get(), d.Normals.get(), d.Ids.get());
      if (!check(cudaGetLastError(), "gather kernel", error))
      {
        return false;
      }
    }
    thrust::lower_bound(thrust::device, keys.get(), keys.get() + n, thrust::counting_iterator<std::uint64_t>(0),
      thrust::counting_iterator<std::uint64_t>(cells + 1), d.CellStart.get());
    if (!check(cudaDeviceSynchronize(), "building the device grid", error))
    {
      return false;
    }
  }
  catch (const thrust::system_error& e)
  {
    error = std::string("thrust: ") + e.what();
    return false;
  }
  catch (const std::bad_alloc&)
  {
    error = "thrust: out of device memory while sorting the grid";
    return false;
  }

  d.Grid = geometry;
  d.Grid.points = d.Points.get();
  d.Grid.normals = d.Normals.get();
  d.Grid.ids = d.Ids.get();
  d.Grid.cellStart = d.CellStart.get(); // the dense index, built on the device whichever the host grid keeps
  d.Grid.rowEntry = nullptr;
  d.Grid.entryX = nullptr;
  d.Grid.entryStart = nullptr;
  return this->prepareBinning(binning, minNeighbors, error);
}

bool CudaScaleSpace::prepare(const MultiresolutionView& pyramid, std::size_t nodeCount, std::size_t cellCount,
  const ScaleBinning& binning, double minNeighbors, std::string& error)
{
  this->State = std::make_unique<Device>();
  Device& d = *this->State;
  const std::size_t topCount = static_cast<std::size_t>(pyramid.topEnd - pyramid.topBegin);
  if (!d.Nodes.upload(pyramid.nodes, nodeCount, error) || !d.Cells.upload(pyramid.cells, cellCount, error) ||
    !d.TopKeys.upload(pyramid.topKeys, topCount, error))
  {
    return false;
  }
  d.Multiresolution = true;
  d.Pyramid = pyramid;
  d.Pyramid.nodes = d.Nodes.get();
  d.Pyramid.cells = d.Cells.get();
  d.Pyramid.topKeys = d.TopKeys.get();
  // The points as the host stores them (StoredPoints.h).
  const StoredPoints& host = pyramid.points;
  const std::size_t n = pyramid.count;
  const bool single = host.positions32 != nullptr;
  const bool singleNormals = host.normals32 != nullptr;
  if ((n > 0 && single && !d.Points32.upload(host.positions32, 3 * n, error)) ||
    (n > 0 && !single && !d.Points.upload(host.positions, n, error)) ||
    (n > 0 && singleNormals && !d.Normals32.upload(host.normals32, 3 * n, error)) ||
    (n > 0 && !singleNormals && !d.Normals.upload(host.normals, n, error)))
  {
    return false;
  }
  d.Pyramid.points.positions = single ? nullptr : d.Points.get();
  d.Pyramid.points.positions32 = single ? d.Points32.get() : nullptr;
  d.Pyramid.points.normals = singleNormals ? nullptr : d.Normals.get();
  d.Pyramid.points.normals32 = singleNormals ? d.Normals32.get() : nullptr;
  return this->prepareBinning(binning, minNeighbors, error);
}

std::size_t CudaScaleSpace::chunkCapacity() const
{
  return this->State ? this->State->Capacity : 0;
}

bool CudaScaleSpace::evaluate(const Vec3* positions, std::size_t count, ScaleSample* out, std::string& error)
{
  if (!this->State || count > this->State->Capacity)
  {
    error = "CudaScaleSpace::evaluate: not prepared, or more positions than chunkCapacity()";
    return false;
  }
  Device& d = *this->State;
  if (count == 0)
  {
    return true;
  }
  const unsigned threads = 128;
  if (!check(cudaMemcpy(d.Positions.get(), positions, count * sizeof(Vec3), cudaMemcpyHostToDevice),
        "cudaMemcpy positions", error))
  {
    return false;
  }
  const unsigned blocks = blocksFor(count, threads);
  if (d.Multiresolution)
  {
    evaluateMultiresolutionByWindowsKernel<kScalesPerWindow><<<blocks, threads>>>(
      d.Pyramid, d.Binning, d.MinNeighbors, d.Positions.get(), count, d.Out.get());
  }
  else
  {
    evaluateByWindowsKernel<kScalesPerWindow><<<blocks, threads>>>(
      d.Grid, d.Binning, d.MinNeighbors, d.Positions.get(), count, d.Out.get());
  }
  return check(cudaGetLastError(), "evaluate kernel launch", error) &&
    check(cudaDeviceSynchronize(), "evaluate kernel", error) &&
    check(cudaMemcpy(out, d.Out.get(), count * d.Binning.count * sizeof(ScaleSample), cudaMemcpyDeviceToHost),
      "cudaMemcpy samples", error);
}

} // namespace gls
