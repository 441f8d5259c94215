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
#include "gls/ShapeOperatorCells.h"
#include "gls/UninitializedArray.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace gls
{

/// The most points an engine takes (its evaluation order and its pyramid's point ranges are 32-bit indices); over it,
/// the engine is left empty (buildAborted(): run() returns false at once).
constexpr std::uint64_t kMaxEnginePoints = 0xffffffffULL;

/// Receives the samples of one point at all scales. Called concurrently from several threads, each call with a
/// distinct pointId: an implementation writes only that point's outputs (or thread-local state).
struct PrincipalCurvatures;

class ScaleSampleSink
{
public:
  virtual ~ScaleSampleSink() = default;
  virtual void consume(std::uint64_t pointId, const ScaleSample* samples, int threadIndex) = 0;
  /// Receives the principal curvatures and directions (ShapeOperator.h) of one point at all scales, on the thread and
  /// just before the consume() of that point, when the engine computes them (ScaleSpaceSettings::
  /// principalCurvatures). A sink that passes samples on passes these on too; the default ignores them.
  virtual void consumeCurvatures(std::uint64_t, const PrincipalCurvatures*, int) {}
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
  /// The pyramid stores its points as floats where every admitted coordinate is a float exactly (StoredPoints.h: the
  /// same samples, 12 bytes a point less for a float32 cloud); false: as doubles always.
  bool singleWhereExact = true;
  /// The pyramid stores the normals as given in floats where every admitted one is a float exactly, normalized when
  /// read (StoredPoints.h: the same samples, 12 bytes a point less, a longer pass); false: unit normals in doubles.
  bool compactNormals = false;
  bool haveBounds = false;            ///< low/high given (else the admitted points' box)
  double low[3] = { 0.0, 0.0, 0.0 };
  double high[3] = { 0.0, 0.0, 0.0 };
};

/// What an engine computes and how: the scales, the evaluation (exact or multi-resolution, with its accuracy in
/// `multiresolution`), the exact evaluation's method and the backend, all chosen once when the engine is built.
struct ScaleSpaceSettings
{
  std::vector<double> scales;   ///< strictly increasing absolute scales (see checkScaleList)
  double minNeighbors = 6.0;    ///< fits with fewer neighbours in the ball are invalid (3 suits 2D curves)
  ParallelOptions parallel;
  Evaluation evaluation = Evaluation::Exact; ///< how each ball's moments are evaluated
  MultiresolutionSettings multiresolution;
  /// The exact evaluation's method (a multi-resolution engine runs its own pass whatever this says).
  EvaluationMethod method = EvaluationMethod::OnePass;
  /// Where the samples are computed: Auto or CUDA run the one pass on the CUDA device when one is usable, and the
  /// engine falls back to the CPU otherwise (or on any CUDA error), saying why (RunReport).
  Backend backend = Backend::CPU;
  std::size_t deviceChunkLimit = 0; ///< CUDA: at most this many points per device pass (0 = as memory allows)
  /// Also the principal curvatures and directions at every scale (ShapeOperator.h), to the sink's consumeCurvatures,
  /// on the CPU (a CUDA backend falls back, saying why): by the exact one pass (whatever `method` says; about 1.6 times
  /// the scale space alone) or the multi-resolution pass, whose engine then keeps the curvature set's cell sums too
  /// (ShapeOperatorCells.h: 496 bytes a summed cell).
  bool principalCurvatures = false;
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

/// The most memory (bytes) an engine's build holds at once, in its two phases: while it makes its sorted copies of the
/// points and normals (reading its inputs), and after that (its cells built, with the scratch of the levels); and what
/// the built engine keeps while it runs.
struct EngineFootprint
{
  double copying = 0.0;
  double built = 0.0;
  double running = 0.0;
  /// The bytes that compact normals (MultiresolutionSettings::compactNormals) would save in each phase: 12 a point
  /// where a multi-resolution engine's normals are floats exactly and it keeps them as unit doubles, else 0.
  double compactNormalsSaving = 0.0;
  /// The peak of the build with `inputBytes` that the caller holds for the inputs and frees when the engine calls
  /// inputsCopied (0 when it keeps them: then its own count): counted while the copies are made, not once the cells
  /// are.
  double bytes(double inputBytes) const { return std::max(inputBytes + this->copying, this->built); }
  /// The peak of a run whose caller allocates `outputs` bytes once the engine is built (a filter's arrays).
  double withOutputs(double inputBytes, double outputs) const
  {
    return std::max(this->bytes(inputBytes), this->running + outputs);
  }
  /// The footprint of the same engine with compact normals.
  EngineFootprint withCompactNormals() const
  {
    const double s = this->compactNormalsSaving;
    return { this->copying - s, this->built - s, this->running - s, 0.0 };
  }
};

/// What a run did: the backend that computed the samples and, when a CUDA run fell back to the CPU, why.
struct RunReport
{
  Backend used = Backend::CPU;
  std::string fallbackReason;
};

class SampleEvaluator;
class CpuSampleEvaluator;
struct RunPoints;

/// The CPU or CUDA engine of the scale space: built once over a cloud, it evaluates any of its points (or any
/// position) at every scale with the evaluator its settings choose (module/src/SampleEvaluators.h).
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
  ~ScaleSpaceEngine();
  ScaleSpaceEngine(ScaleSpaceEngine&&) noexcept;
  ScaleSpaceEngine& operator=(ScaleSpaceEngine&&) noexcept;

  /// The most memory an engine over these points holds at once, its build's scratch included, for a budget checked
  /// before it is built: its order and sorted copies, and its grid's index (exact) or its pyramid (multi-resolution:
  /// the pyramid's nodes counted from the points' sorted finest keys, 0.65 s at 10M points where the build takes
  /// 2.2 s). bytes(0) is at least memoryBytes() of the engine built (tested).
  static EngineFootprint footprint(
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
  const UninitializedArray<std::uint32_t>& evaluationOrder() const { return this->Order; }

  /// Evaluates the given points (all when ids is null) and feeds the sink, in an order of the engine's choosing (a
  /// multi-resolution engine takes a few given points, under a quarter of them, in pyramid order), with the
  /// evaluator of its settings: on the CUDA device when the backend asks for it and the device can run it, else on
  /// the CPU, `report` saying which and, when the device was asked for but not used, why. `parallel` overrides the
  /// settings' threads and progress callback for this run. Returns false if aborted.
  bool run(ScaleSampleSink& sink, const std::vector<std::uint64_t>* ids = nullptr,
    const ParallelOptions* parallel = nullptr, RunReport* report = nullptr) const;

  /// Evaluates an arbitrary position (not necessarily a data point) at all scales, on the calling thread (the CPU
  /// evaluator of the settings).
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
  void orderGivenIds(const std::vector<std::uint64_t>& ids, int threads, UninitializedArray<std::uint32_t>& order,
    UninitializedArray<std::uint64_t>& slots) const;
  /// The points of a run (their ids, and the slots of a caller's order: null for the engine's own), their positions
  /// read from the sorted copy and RestPositions.
  RunPoints pointsOfRun(const std::uint32_t* order, std::size_t count, const std::uint64_t* slots) const;
  /// The points of the grid or pyramid, in their sorted order: Order's first sortedCount() ids.
  StoredPoints sortedPoints() const;
  std::size_t sortedCount() const;
  /// The evaluators of the settings, once the grid or pyramid is built: the CPU's, and the device's when the backend
  /// asks for one and it can run (else DeviceRefusal says why).
  void chooseEvaluators();

  ScaleSpaceSettings Settings;
  std::vector<double> SquaredScales;
  BinningTable BinTable;
  std::size_t Count = 0;                ///< the points given (evaluated ids are below it)
  UninitializedArray<std::uint32_t> Order; ///< evaluation order: grid order first (locality), then the rest
  /// The positions of the rest (Order's ids from sortedCount() on: the points left out of the grid or pyramid, NaN
  /// allowed); the others' positions are the sorted copy's (no copy of every position is kept: 24 bytes a point).
  UninitializedArray<Vec3> RestPositions;
  NeighborGrid Grid;                    ///< exact evaluation
  MultiresolutionCloud Pyramid;         ///< multi-resolution evaluation
  bool BuildAborted = false;
  /// The principal curvatures' cell sums of the pyramid (summedCellsOf), when the settings ask for the curvatures.
  std::vector<CurvatureCell> CurvatureCells;
  std::unique_ptr<CpuSampleEvaluator> Cpu; ///< always (the fallback of the device's)
  std::unique_ptr<SampleEvaluator> Device; ///< when the backend asks for the device and it can run the settings
  std::string DeviceRefusal;               ///< why the device was asked for but not chosen (empty otherwise)
};

} // namespace gls
