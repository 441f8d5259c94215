// The CUDA evaluator (SampleEvaluators.h): the engine's grid or pyramid uploaded at each run, its points evaluated in
// chunks on the device, each chunk's samples fed to the sink on the CPU's threads.
#include "SampleEvaluators.h"

#include "gls/ScaleSpaceEngine.h"

#include <algorithm>
#include <vector>

namespace gls
{
namespace
{

class CudaEvaluator : public SampleEvaluator
{
public:
  CudaEvaluator(const GridView& grid, const MultiresolutionView* pyramid, std::size_t nodeCount, std::size_t cellCount,
    const EvaluatorBasis& basis, std::size_t chunkLimit)
    : Grid(grid)
    , HasPyramid(pyramid != nullptr)
    , NodeCount(nodeCount)
    , CellCount(cellCount)
    , Basis(basis)
    , ChunkLimit(chunkLimit)
  {
    if (pyramid)
    {
      this->Pyramid = *pyramid;
    }
  }

  Backend backend() const override { return Backend::CUDA; }

  bool run(const RunPoints& points, ScaleSampleSink& sink, const ParallelOptions& options, bool& aborted,
    std::string& failure) const override
  {
    aborted = false;
    const std::size_t S = this->Basis.scaleCount();
    CudaScaleSpace device;
    const bool prepared = this->HasPyramid
      ? device.prepare(this->Pyramid, this->NodeCount, this->CellCount, this->Basis.binning, this->Basis.minNeighbors,
          failure)
      : device.prepare(this->Grid, this->Basis.binning, this->Basis.minNeighbors, failure);
    if (!prepared)
    {
      return false;
    }
    std::size_t chunk = device.chunkCapacity();
    if (this->ChunkLimit > 0)
    {
      chunk = std::min(chunk, this->ChunkLimit);
    }
    std::vector<Vec3> positions;
    std::vector<ScaleSample> samples;
    ParallelOptions feed;
    feed.threads = options.threads;
    for (std::size_t begin = 0; begin < points.count; begin += chunk)
    {
      const std::size_t count = std::min(chunk, points.count - begin);
      positions.resize(count);
      samples.resize(count * S);
      for (std::size_t i = 0; i < count; ++i)
      {
        positions[i] = points.positionAt(begin + i);
      }
      if (!device.evaluate(positions.data(), count, samples.data(), failure))
      {
        return false;
      }
      parallelFor(count, feed, [&](std::size_t b, std::size_t e, int thread) {
        for (std::size_t i = b; i < e; ++i)
        {
          sink.consume(points.order[begin + i], samples.data() + i * S, thread);
        }
      });
      if (options.progress && options.progress(static_cast<double>(begin + count) / points.count))
      {
        aborted = true;
        return false;
      }
    }
    return true;
  }

private:
  GridView Grid;
  MultiresolutionView Pyramid;
  bool HasPyramid;
  std::size_t NodeCount;
  std::size_t CellCount;
  EvaluatorBasis Basis;
  std::size_t ChunkLimit;
};

} // namespace

std::unique_ptr<SampleEvaluator> makeCudaEvaluator(const GridView& grid, const MultiresolutionView* pyramid,
  std::size_t nodeCount, std::size_t cellCount, const EvaluatorBasis& basis, std::size_t chunkLimit)
{
  return std::make_unique<CudaEvaluator>(grid, pyramid, nodeCount, cellCount, basis, chunkLimit);
}

} // namespace gls
