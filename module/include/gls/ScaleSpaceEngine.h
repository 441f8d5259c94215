// The CPU scale-space engine: builds the neighbour grid once, then evaluates every point at every scale on all
// threads and hands each point's samples to a sink. Neighbourhoods hold only points with finite coordinates and a
// finite non-zero normal (normals are normalized); every point with finite coordinates is evaluated, the others get
// invalid (NaN) samples. Results do not depend on the thread count (each point is computed alone).
#pragma once

#include "gls/Backend.h"
#include "gls/Evaluation.h"
#include "gls/MultiresolutionCloud.h"
#include "gls/NeighborGrid.h"
#include "gls/ParallelFor.h"
#include "gls/PointScaleSpace.h"
#include "gls/ScaleSample.h"
#include "gls/ScaleSampling.h"
#include "gls/UninitializedArray.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace gls
{

/// Receives the samples of one point at all scales. Called concurrently from several threads, each call with a
/// distinct pointId: an implementation writes only that point's outputs (or thread-local state).
class ScaleSampleSink
{
public:
  virtual ~ScaleSampleSink() = default;
  virtual void consume(std::uint64_t pointId, const ScaleSample* samples, int threadIndex) = 0;
};

/// The multi-resolution evaluation's parameters (used when ScaleSpaceSettings::evaluation is Multiresolution).
/// A distributed run passes the global box and spacing, so that every piece lays its pyramid out like a serial run.
struct MultiresolutionSettings
{
  double accuracy = kDefaultAccuracy; ///< epsilon: a cell is one sample where edge <= epsilon * distance
  /// Cells at least this many walk-region half-diagonals away enter linearized (MultiresolutionFarRule.h,
  /// kLinearizedDistance); 0: none (every cell's shares formed for each point).
  double linearizedDistance = kLinearizedDistance;
  double spacing = 0.0;               ///< typical neighbour distance (length unit); 0: surfaceSpacingOfBox of the
                                      ///< admitted points
  bool haveBounds = false;            ///< low/high given (else the admitted points' box)
  double low[3] = { 0.0, 0.0, 0.0 };
  double high[3] = { 0.0, 0.0, 0.0 };
};

struct ScaleSpaceSettings
{
  std::vector<double> scales;   ///< strictly increasing absolute scales (see checkScaleList)
  double minNeighbors = 6.0;    ///< fits with fewer neighbours in the ball are invalid (3 suits 2D curves)
  ParallelOptions parallel;
  std::size_t deviceChunkLimit = 0; ///< CUDA: at most this many points per device pass (0 = as memory allows)
  Evaluation evaluation = Evaluation::Exact; ///< how each ball's moments are evaluated
  MultiresolutionSettings multiresolution;
  /// The exact evaluation's grid lattice when given (a spatial tile of a larger cloud takes the whole cloud's, so that
  /// its sums equal the whole run's bit for bit: TiledScaleSpace); else exactGridLattice of the points.
  bool haveGridLattice = false;
  GridLattice gridLattice;
};

/// The lattice of an exact evaluation's grid over these points (admit: the admitOrientedPoints flags): cells of a
/// quarter of the largest scale, enlarged where the grid would need too many cells (NeighborGrid::chooseLattice).
GridLattice exactGridLattice(
  const double* points, std::size_t count, const unsigned char* admit, const std::vector<double>& scales);

/// Fills in what the multi-resolution layout takes from the cloud when the settings leave it out: the box of the
/// admitted points (haveBounds) and the spacing (surfaceSpacingOfBox of that box and the admitted count).
void resolvePyramidFrame(
  MultiresolutionSettings& m, const double* points, std::size_t count, const unsigned char* admit);

/// What a run did: the backend that computed the samples and, when a CUDA run fell back to the CPU, why.
struct RunReport
{
  Backend used = Backend::CPU;
  std::string fallbackReason;
};

enum class EvaluationMethod
{
  OnePass,   ///< all scales from one gather (the moment formulation); the default
  PerScale   ///< one ball query and one weighted fit per scale (reference and benchmark baseline)
};

class ScaleSpaceEngine
{
public:
  /// points, normals: count interleaved xyz triples (copied into the grid or pyramid, sorted; the caller's buffers
  /// need not outlive the constructor). `inputsCopied`, when given, is called once the engine has read them for the
  /// last time, before its build ends (its sorted copies are made; the cells and their sums not yet), so that a caller
  /// can free them while the rest is built (at 10M points: 458 MiB of doubles). A multi-resolution engine builds its
  /// pyramid here on settings.parallel's threads, reporting settings.parallel.progress; when that asks to abort, the
  /// engine is left empty (buildAborted()).
  ScaleSpaceEngine(const double* points, const double* normals, std::size_t count, ScaleSpaceSettings settings,
    const std::function<void()>& inputsCopied = nullptr);

  /// The most memory (bytes) an engine over these points holds at once, its build's scratch included, for a budget
  /// checked before it is built: its positions and order, and its grid (exact) or its pyramid (multi-resolution: the
  /// pyramid's nodes counted from the points' sorted finest keys, 0.65 s at 10M points where the build takes 2.2 s).
  /// At least memoryBytes() of the engine built (tested).
  static double footprint(
    const double* points, const double* normals, std::size_t count, const ScaleSpaceSettings& settings);
  /// The bytes the built engine's arrays hold (their capacity).
  double memoryBytes() const;

  std::size_t pointCount() const { return this->Count; }
  const std::vector<double>& scales() const { return this->Settings.scales; }
  Evaluation evaluation() const { return this->Settings.evaluation; }
  /// True when the progress callback stopped the pyramid's build (run() then returns false at once).
  bool buildAborted() const { return this->BuildAborted; }
  /// The multi-resolution pyramid (empty for an exact engine).
  const MultiresolutionCloud& pyramid() const { return this->Pyramid; }
  /// The order a run without ids evaluates the points in (grid order first, for locality; then the points left out
  /// of the grid). A caller that evaluates a subset (e.g. the owned points of a distributed piece, not its ghosts)
  /// keeps locality by filtering this order.
  const UninitializedArray<std::uint64_t>& evaluationOrder() const { return this->Order; }

  /// Evaluates the given points (all when ids is null) and feeds the sink, in an order of the engine's choosing (a
  /// multi-resolution engine takes a few given points, under a quarter of them, in pyramid order). A multi-resolution
  /// engine runs its pass whatever `method` says (the per-scale reference is of the exact evaluation). `parallel`
  /// overrides the settings' threads and progress callback for this run. `backend` Auto or CUDA runs the one-pass
  /// method on the CUDA device when one is usable and falls back to the CPU otherwise (or on any CUDA error), saying
  /// why in `report`. Returns false if aborted.
  bool run(ScaleSampleSink& sink, const std::vector<std::uint64_t>* ids = nullptr,
    EvaluationMethod method = EvaluationMethod::OnePass, const ParallelOptions* parallel = nullptr,
    Backend backend = Backend::CPU, RunReport* report = nullptr) const;

  /// Evaluates an arbitrary position (not necessarily a data point) at all scales, on the calling thread.
  void evaluatePosition(const Vec3& p, std::vector<ScaleSample>& out) const;

private:
  ScaleBinning binning() const;
  /// The pyramid's layout for these points under the settings (the box and spacing of the admitted points where the
  /// settings leave them out).
  static PyramidLayout pyramidLayout(
    const ScaleSpaceSettings& settings, const double* points, std::size_t count, const unsigned char* admit);
  void buildPyramid(const double* points, const double* normals, std::size_t count, const unsigned char* admit,
    const std::function<void()>& inputsCopied);
  /// The slot (index in Order) of every given id, in their order: through a bitmap of the ids for a short list, the
  /// inverse of Order for a long one (no array of Count values for a few ids).
  UninitializedArray<std::uint64_t> slotsOf(const std::vector<std::uint64_t>& ids, int threads) const;
  /// The given ids (and their slots) in the order a run takes them: a multi-resolution run given a sample (under
  /// 1 / kSampleFraction of the points) takes it in pyramid order, any other run as given.
  void orderGivenIds(const std::vector<std::uint64_t>& ids, int threads, UninitializedArray<std::uint64_t>& order,
    UninitializedArray<std::uint64_t>& slots) const;
  /// The points of the grid or pyramid, in their sorted order: Order's first sortedCount() ids.
  const Vec3* sortedPositions() const;
  std::size_t sortedCount() const;
  /// The position of the point at index `slot` of Order: the sorted copy's, or else RestPositions'.
  const Vec3& positionInSlot(std::uint64_t slot, const Vec3* sorted, std::size_t sortedCount) const
  {
    return slot < sortedCount ? sorted[slot] : this->RestPositions[slot - sortedCount];
  }
  /// The run on the CUDA device when `backend` asks for it and it can run there: true when it ran there (r.used
  /// CUDA); false to run on the CPU, with r.fallbackReason saying why unless the CPU was asked for, or with `aborted`
  /// set when the progress callback asked to stop.
  bool runOnDeviceIfAsked(ScaleSampleSink& sink, const std::uint64_t* order, std::size_t orderSize,
    const std::uint64_t* slots, EvaluationMethod method, const ParallelOptions& options, Backend backend, RunReport& r,
    bool& aborted) const;
  /// The run on the CPU, with the evaluation chosen once for every point (multi-resolution, one pass, or per scale).
  bool runOnCpu(ScaleSampleSink& sink, const std::uint64_t* order, std::size_t orderSize,
    const std::uint64_t* slots, EvaluationMethod method, const ParallelOptions& options) const;
  /// Feeds the sink with every point of `order` in parallel: evaluateAt(p, thread, samples) for a finite position,
  /// invalid samples for another. `slots`: the slot of each point of a caller's order (orderGivenIds); null for the
  /// engine's own order (the k-th point's slot is k).
  template <typename EvaluateAt>
  bool forEachPoint(ScaleSampleSink& sink, const std::uint64_t* order, std::size_t orderSize,
    const std::uint64_t* slots, const ParallelOptions& cpu, const EvaluateAt& evaluateAt) const;
  /// The CUDA run: false with `reason` on a CUDA failure (nothing was fed to the sink), false with `aborted` set
  /// when the progress callback asked to stop.
  bool runOnDevice(ScaleSampleSink& sink, const std::uint64_t* order, std::size_t orderSize,
    const std::uint64_t* slots, const ParallelOptions& options, std::string& reason, bool& aborted) const;

  ScaleSpaceSettings Settings;
  std::vector<double> SquaredScales;
  BinningTable BinTable;
  std::size_t Count = 0;                ///< the points given (evaluated ids are below it)
  UninitializedArray<std::uint64_t> Order; ///< evaluation order: grid order first (locality), then the rest
  /// The positions of the rest (Order's ids from sortedCount() on: the points left out of the grid or pyramid, NaN
  /// allowed); the others' positions are the sorted copy's (no copy of every position is kept: 24 bytes a point).
  UninitializedArray<Vec3> RestPositions;
  NeighborGrid Grid;                    ///< exact evaluation
  MultiresolutionCloud Pyramid;         ///< multi-resolution evaluation
  bool BuildAborted = false;
};

} // namespace gls
