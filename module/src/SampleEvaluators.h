// The evaluators of a scale-space engine: one per way of computing a point's samples at every scale, behind one
// interface. On the CPU: the exact one pass, the exact per-scale reference and the multi-resolution pass; on a CUDA
// device: the one pass on the grid or the pyramid. ScaleSpaceEngine chooses them once, when it is built, from its
// settings (evaluation, method, backend), and falls back from the device's to the CPU's in one place (its run()).
// A new backend is a new SampleEvaluator and one branch in ScaleSpaceEngine::chooseEvaluators (docs/architecture.md,
// "How to add a backend"; Testing/Core/TestBackendOfATestFit.cpp implements one).
#pragma once

#include "gls/Backend.h"
#include "gls/GridView.h"
#include "gls/MultiresolutionView.h"
#include "gls/Numeric.h"
#include "gls/ParallelFor.h"
#include "gls/PointScaleSpace.h"
#include "gls/ScaleSample.h"
#include "gls/ScaleSpaceEngine.h"
#include "gls/ShapeOperatorCells.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace gls
{

/// The points of one run: the k-th has the id order[k] (what the sink sees) and the position positionAt(k), read
/// from the engine's sorted copy (its slot is k for the engine's own order, slots[k] for a caller's) or, past it,
/// from the positions of the points left out of the grid or pyramid.
struct RunPoints
{
  const std::uint32_t* order = nullptr;
  std::size_t count = 0;
  const std::uint64_t* slots = nullptr; ///< null: the engine's own order
  StoredPoints sorted;
  std::size_t sortedCount = 0;
  const Vec3* rest = nullptr;

  Vec3 positionAt(std::size_t k) const
  {
    const std::uint64_t slot = this->slots ? this->slots[k] : k;
    return slot < this->sortedCount ? this->sorted.position(slot) : this->rest[slot - this->sortedCount];
  }
};

/// What every evaluator reads: the scales' binning and the fewest neighbours of a valid fit.
struct EvaluatorBasis
{
  ScaleBinning binning;
  double minNeighbors = 0.0;
  std::size_t scaleCount() const { return static_cast<std::size_t>(this->binning.count); }
};

/// Evaluates every point of the run in parallel on the CPU's threads (the CPU evaluators' loop, and any evaluator's
/// that computes point by point on the host) and delivers each point's S samples of type Sample: evaluateAt(p,
/// thread, samples) at a finite position, `invalid` at another, then deliver(id, samples, thread). A run in the
/// engine's own order reads its positions from the sorted copy in that order (through a copy in input order, each
/// point cost a cache miss: 2% of a 10M-point run).
template <typename Sample, typename EvaluateAt, typename Deliver>
bool evaluateEachPoint(const RunPoints& points, std::size_t S, const Sample& invalid, const ParallelOptions& cpu,
  const EvaluateAt& evaluateAt, const Deliver& deliver)
{
  std::vector<std::vector<Sample>> samples(static_cast<std::size_t>(resolveThreadCount(cpu.threads)));
  return parallelFor(points.count, cpu, [&](std::size_t begin, std::size_t end, int thread) {
    std::vector<Sample>& out = samples[static_cast<std::size_t>(thread)];
    out.resize(S);
    for (std::size_t k = begin; k < end; ++k)
    {
      const Vec3& p = points.positionAt(k);
      if (!(isFinite(p.x) && isFinite(p.y) && isFinite(p.z)))
      {
        for (std::size_t s = 0; s < S; ++s)
        {
          out[s] = invalid;
        }
      }
      else
      {
        evaluateAt(p, thread, out.data());
      }
      deliver(points.order[k], out.data(), thread);
    }
  });
}

/// evaluateEachPoint for the oriented sphere's samples, fed to the sink.
template <typename EvaluateAt>
bool feedEachPoint(const RunPoints& points, std::size_t S, ScaleSampleSink& sink, const ParallelOptions& cpu,
  const EvaluateAt& evaluateAt)
{
  return evaluateEachPoint(points, S, invalidSample<double>(0.0), cpu, evaluateAt,
    [&sink](std::uint64_t id, const ScaleSample* s, int thread) { sink.consume(id, s, thread); });
}

/// Computes the samples of a run's points and feeds them to a sink.
class SampleEvaluator
{
public:
  virtual ~SampleEvaluator() = default;
  /// Where it computes.
  virtual Backend backend() const = 0;
  /// Feeds the sink with the samples of every point of `points` (invalid samples at a non-finite position), on
  /// options' threads and reporting options.progress. False when the progress callback asked to stop (`aborted`
  /// set) or when a device failed (`failure` says why; the sink was then fed nothing).
  virtual bool run(const RunPoints& points, ScaleSampleSink& sink, const ParallelOptions& options, bool& aborted,
    std::string& failure) const = 0;
};

/// The CPU evaluators, which also evaluate one position on the calling thread (ScaleSpaceEngine::evaluatePosition).
class CpuSampleEvaluator : public SampleEvaluator
{
public:
  Backend backend() const override { return Backend::CPU; }
  /// The samples (scaleCount of them) of a finite position.
  virtual void evaluatePosition(const Vec3& p, ScaleSample* out) const = 0;
};

/// The exact one pass: every point of the ball at every scale from one gather (OnePassKernel.h).
std::unique_ptr<CpuSampleEvaluator> makeOnePassEvaluator(const GridView& grid, const EvaluatorBasis& basis);
/// The exact per-scale reference: one ball query and one weighted fit per scale (evaluateOneScale).
std::unique_ptr<CpuSampleEvaluator> makePerScaleEvaluator(const GridView& grid, const EvaluatorBasis& basis);
/// The exact one pass with the principal curvatures (ShapeOperatorMoments): each point's curvatures to the sink's
/// consumeCurvatures, then its sphere samples to consume.
std::unique_ptr<CpuSampleEvaluator> makeOnePassCurvatureEvaluator(const GridView& grid, const EvaluatorBasis& basis);
/// The multi-resolution pass over the pyramid (MultiresolutionKernel.h).
std::unique_ptr<CpuSampleEvaluator> makeMultiresolutionEvaluator(
  const MultiresolutionView& pyramid, const EvaluatorBasis& basis);

/// The multi-resolution pass with the principal curvatures (ShapeOperatorMoments), from the curvature set's cell
/// sums (summedCellsOf of the pyramid): each point's curvatures to consumeCurvatures, then its sphere samples.
std::unique_ptr<CpuSampleEvaluator> makeMultiresolutionCurvatureEvaluator(
  const MultiresolutionView& pyramid, const CurvatureCell* cells, const EvaluatorBasis& basis);

/// The CUDA one pass on the engine's grid, or on its pyramid (pyramid non-null: with its nodeCount nodes and
/// cellCount summed cells), in chunks of at most chunkLimit points (0: as the device's memory allows). Its run()
/// uploads them and fails (with the reason) where the device cannot take them.
std::unique_ptr<SampleEvaluator> makeCudaEvaluator(const GridView& grid, const MultiresolutionView* pyramid,
  std::size_t nodeCount, std::size_t cellCount, const EvaluatorBasis& basis, std::size_t chunkLimit);

} // namespace gls
