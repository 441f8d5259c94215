// The CPU evaluators (SampleEvaluators.h): the exact one pass, the exact per-scale reference and the multi-resolution
// pass, each a per-point function fed through one parallel loop over the run's points.
#include "SampleEvaluators.h"

#include "gls/MultiresolutionKernel.h"
#include "gls/Numeric.h"
#include "gls/OnePassKernel.h"
#include "gls/ScaleSpaceEngine.h"

#include <algorithm>
#include <vector>

namespace gls
{
namespace
{

/// The fewest points per chunk of a multi-resolution run on the CPU (ParallelOptions::chunk): each chunk's first point
/// walks anew. Measured on the bunny at 3M points (2 threads): 53,900 far walks and 203,500 walks with 4096 against
/// 64,500 and 213,500 with 256; a chunk of 4096 points still takes well under a second.
constexpr std::size_t kMultiresolutionChunk = 4096;

/// The fewest chunks per thread that a multi-resolution run's larger chunks leave (the load's balance at the end).
constexpr std::size_t kChunksPerThread = 8;

/// evaluateEachPoint for the curvature set's samples: each point's principal curvatures to the sink's
/// consumeCurvatures, then its sphere samples to consume.
template <typename EvaluateAt>
bool feedEachPointWithCurvatures(const RunPoints& points, std::size_t S, ScaleSampleSink& sink,
  const ParallelOptions& options, const EvaluateAt& evaluateAt)
{
  const std::size_t threads = static_cast<std::size_t>(resolveThreadCount(options.threads));
  std::vector<std::vector<ScaleSample>> spheres(threads, std::vector<ScaleSample>(S));
  std::vector<std::vector<PrincipalCurvatures>> curvatures(threads, std::vector<PrincipalCurvatures>(S));
  const CurvatureSample invalid{ invalidSample<double>(0.0), undefinedCurvatures() };
  return evaluateEachPoint(points, S, invalid, options, evaluateAt,
    [&](std::uint64_t id, const CurvatureSample* samples, int t) {
      std::vector<ScaleSample>& sphere = spheres[static_cast<std::size_t>(t)];
      std::vector<PrincipalCurvatures>& principal = curvatures[static_cast<std::size_t>(t)];
      for (std::size_t k = 0; k < S; ++k)
      {
        sphere[k] = samples[k].sphere;
        principal[k] = samples[k].principal;
      }
      sink.consumeCurvatures(id, principal.data(), t);
      sink.consume(id, sphere.data(), t);
    });
}

/// The multi-resolution pass's chunk: at least kMultiresolutionChunk points (consecutive points share their walks;
/// a chunk's first point walks anew: at 256 points per chunk that added 16% more far walks at 3M points), and at
/// least kChunksPerThread chunks per thread, so that a small run (a sample of scattered points) stays balanced.
ParallelOptions multiresolutionChunks(const ParallelOptions& options, std::size_t points)
{
  const std::size_t threads = static_cast<std::size_t>(resolveThreadCount(options.threads));
  ParallelOptions cpu = options;
  const std::size_t balanced = points / (kChunksPerThread * threads);
  cpu.chunk = std::max(cpu.chunk, std::min(kMultiresolutionChunk, balanced));
  return cpu;
}

/// What the exact evaluators read: the grid and the basis.
class GridEvaluator : public CpuSampleEvaluator
{
public:
  GridEvaluator(const GridView& grid, const EvaluatorBasis& basis)
    : Grid(grid)
    , Basis(basis)
  {
  }

protected:
  GridView Grid;
  EvaluatorBasis Basis;
};

class OnePassEvaluator : public GridEvaluator
{
public:
  using GridEvaluator::GridEvaluator;

  bool run(const RunPoints& points, ScaleSampleSink& sink, const ParallelOptions& options, bool& aborted,
    std::string&) const override
  {
    // Each thread's bins, allocated by the thread that uses them (from its own heap arena): allocated here, the exact
    // pass on the bunny at 1M points (2 threads, 10 scales) took 19.9-20.0 s, against 18.2-18.6 s.
    const std::size_t S = this->Basis.scaleCount();
    std::vector<std::vector<Moments>> bins(static_cast<std::size_t>(resolveThreadCount(options.threads)));
    aborted = !feedEachPoint(points, S, sink, options, [&](const Vec3& p, int t, ScaleSample* out) {
      std::vector<Moments>& b = bins[static_cast<std::size_t>(t)];
      if (b.size() != S)
      {
        b.resize(S);
      }
      evaluateAllScalesOnCpu(this->Grid, p, this->Basis.binning, this->Basis.minNeighbors, b.data(), out);
    });
    return !aborted;
  }

  void evaluatePosition(const Vec3& p, ScaleSample* out) const override
  {
    std::vector<Moments> b(this->Basis.scaleCount());
    evaluateAllScalesOnCpu(this->Grid, p, this->Basis.binning, this->Basis.minNeighbors, b.data(), out);
  }
};

/// The one pass with the principal curvatures: a point's curvatures to consumeCurvatures, then its sphere samples
/// (evaluatePosition: the one pass's sphere samples alone).
class OnePassCurvatureEvaluator : public OnePassEvaluator
{
public:
  using OnePassEvaluator::OnePassEvaluator;

  bool run(const RunPoints& points, ScaleSampleSink& sink, const ParallelOptions& options, bool& aborted,
    std::string&) const override
  {
    const std::size_t S = this->Basis.scaleCount();
    std::vector<std::vector<MomentsT<ShapeOperatorMoments>>> bins(
      static_cast<std::size_t>(resolveThreadCount(options.threads)));
    aborted = !feedEachPointWithCurvatures(points, S, sink, options, [&](const Vec3& p, int t, CurvatureSample* out) {
      std::vector<MomentsT<ShapeOperatorMoments>>& b = bins[static_cast<std::size_t>(t)];
      b.resize(S);
      evaluateAllScalesOnCpu(this->Grid, p, this->Basis.binning, this->Basis.minNeighbors, b.data(), out);
    });
    return !aborted;
  }
};

class PerScaleEvaluator : public GridEvaluator
{
public:
  using GridEvaluator::GridEvaluator;

  bool run(const RunPoints& points, ScaleSampleSink& sink, const ParallelOptions& options, bool& aborted,
    std::string&) const override
  {
    aborted = !feedEachPoint(points, this->Basis.scaleCount(), sink, options,
      [this](const Vec3& p, int, ScaleSample* out) { this->evaluatePosition(p, out); });
    return !aborted;
  }

  void evaluatePosition(const Vec3& p, ScaleSample* out) const override
  {
    for (std::size_t k = 0; k < this->Basis.scaleCount(); ++k)
    {
      out[k] = evaluateOneScale(this->Grid, p, this->Basis.binning.scales[k], this->Basis.minNeighbors);
    }
  }
};

class MultiresolutionEvaluator : public CpuSampleEvaluator
{
public:
  MultiresolutionEvaluator(const MultiresolutionView& pyramid, const EvaluatorBasis& basis)
    : Pyramid(pyramid)
    , Basis(basis)
  {
  }

  bool run(const RunPoints& points, ScaleSampleSink& sink, const ParallelOptions& options, bool& aborted,
    std::string&) const override
  {
    // Consecutive points in pyramid order share their walks (MultiresolutionScratch keeps a thread's last ones).
    const ParallelOptions cpu = multiresolutionChunks(options, points.count);
    std::vector<MultiresolutionScratch> scratch(static_cast<std::size_t>(resolveThreadCount(options.threads)));
    aborted = !feedEachPoint(points, this->Basis.scaleCount(), sink, cpu, [&](const Vec3& p, int t, ScaleSample* out) {
      evaluateAllScalesMultiresolutionOnCpu(this->Pyramid, p, this->Basis.binning, this->Basis.minNeighbors,
        scratch[static_cast<std::size_t>(t)], out);
    });
    return !aborted;
  }

  void evaluatePosition(const Vec3& p, ScaleSample* out) const override
  {
    MultiresolutionScratch scratch;
    evaluateAllScalesMultiresolutionOnCpu(
      this->Pyramid, p, this->Basis.binning, this->Basis.minNeighbors, scratch, out);
  }

protected:
  MultiresolutionView Pyramid;
  EvaluatorBasis Basis;
};

/// The multi-resolution pass with the principal curvatures, from the curvature set's cell sums (evaluatePosition:
/// the multi-resolution pass's sphere samples alone).
class MultiresolutionCurvatureEvaluator : public MultiresolutionEvaluator
{
public:
  MultiresolutionCurvatureEvaluator(
    const MultiresolutionView& pyramid, const CurvatureCell* cells, const EvaluatorBasis& basis)
    : MultiresolutionEvaluator(pyramid, basis)
    , Cells(cells)
  {
  }

  bool run(const RunPoints& points, ScaleSampleSink& sink, const ParallelOptions& options, bool& aborted,
    std::string&) const override
  {
    const ParallelOptions cpu = multiresolutionChunks(options, points.count);
    std::vector<MultiresolutionScratchT<ShapeOperatorMoments>> scratch(
      static_cast<std::size_t>(resolveThreadCount(options.threads)));
    aborted = !feedEachPointWithCurvatures(
      points, this->Basis.scaleCount(), sink, cpu, [&](const Vec3& p, int t, CurvatureSample* out) {
        evaluateAllScalesMultiresolutionOnCpu(this->Pyramid, this->Cells, p, this->Basis.binning,
          this->Basis.minNeighbors, scratch[static_cast<std::size_t>(t)], out);
      });
    return !aborted;
  }

private:
  const CurvatureCell* Cells;
};

} // namespace

std::unique_ptr<CpuSampleEvaluator> makeOnePassEvaluator(const GridView& grid, const EvaluatorBasis& basis)
{
  return std::make_unique<OnePassEvaluator>(grid, basis);
}

std::unique_ptr<CpuSampleEvaluator> makeOnePassCurvatureEvaluator(const GridView& grid, const EvaluatorBasis& basis)
{
  return std::make_unique<OnePassCurvatureEvaluator>(grid, basis);
}

std::unique_ptr<CpuSampleEvaluator> makePerScaleEvaluator(const GridView& grid, const EvaluatorBasis& basis)
{
  return std::make_unique<PerScaleEvaluator>(grid, basis);
}

std::unique_ptr<CpuSampleEvaluator> makeMultiresolutionEvaluator(
  const MultiresolutionView& pyramid, const EvaluatorBasis& basis)
{
  return std::make_unique<MultiresolutionEvaluator>(pyramid, basis);
}

std::unique_ptr<CpuSampleEvaluator> makeMultiresolutionCurvatureEvaluator(
  const MultiresolutionView& pyramid, const CurvatureCell* cells, const EvaluatorBasis& basis)
{
  return std::make_unique<MultiresolutionCurvatureEvaluator>(pyramid, cells, basis);
}

} // namespace gls
