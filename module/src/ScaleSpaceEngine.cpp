#include "gls/ScaleSpaceEngine.h"

#include "SampleEvaluators.h"

#include "gls/KeySort.h"
#include "gls/MultiresolutionCellSums.h"
#include "gls/Numeric.h"
#include "gls/PointBox.h"
#include "gls/PointScaleSpace.h"
#include "gls/ScaleSampling.h"
#include "gls/ShapeOperator.h"

#include <algorithm>
#include <utility>

namespace gls
{
namespace
{

/// A multi-resolution run given fewer than 1 / kSampleFraction of the points takes them in pyramid order.
constexpr std::size_t kSampleFraction = 4;

/// The exact grid's cells: a quarter of the largest scale, few candidates outside the ball (measured: 6.2 s against
/// 7.1 s at half).
double exactGridCellSize(const std::vector<double>& scales)
{
  return scales.empty() ? 0.0 : 0.25 * scales.back();
}

} // namespace

GridLattice exactGridLattice(
  const double* points, std::size_t count, const unsigned char* admit, const std::vector<double>& scales)
{
  return NeighborGrid::chooseLattice(points, count, exactGridCellSize(scales), admit);
}

void resolvePyramidFrame(
  MultiresolutionSettings& m, const double* points, std::size_t count, const unsigned char* admit)
{
  const PointBox box = boxOfFinitePoints(points, count, admit); // admitted points are finite
  if (!m.haveBounds)
  {
    std::copy(box.low, box.low + 3, m.low);
    std::copy(box.high, box.high + 3, m.high);
  }
  m.haveBounds = true;
  if (!(m.spacing > 0.0))
  {
    m.spacing = surfaceSpacingOfBox(m.low, m.high, box.count);
  }
}

ScaleSpaceEngine::ScaleSpaceEngine(const double* points, const double* normals, std::size_t count,
  ScaleSpaceSettings settings, const std::function<void()>& inputsCopied)
  : Settings(std::move(settings))
  , Count(count)
{
  for (double t : this->Settings.scales)
  {
    this->SquaredScales.push_back(t * t);
  }
  this->BinTable = makeBinningTable(this->SquaredScales);
  if (count > kMaxEnginePoints)
  {
    this->BuildAborted = true;
    return;
  }
  // Points whose normal cannot be normalized stay out of every neighbourhood. (The large arrays are written whole by
  // parallel loops: their pages are first touched on every thread.)
  const int threads = this->Settings.parallel.threads;
  const bool multiresolution =
    this->Settings.evaluation == Evaluation::Multiresolution && !this->Settings.scales.empty();
  UninitializedArray<unsigned char> admit(count);
  UninitializedArray<double> unitNormals; // the exact evaluation's (the pyramid normalizes as it sorts)
  if (multiresolution)
  {
    admitOrientedPoints(points, normals, count, admit.data(), threads);
  }
  else
  {
    unitNormals.resize(3 * count);
    normalizeAndAdmit(points, normals, count, unitNormals.data(), admit.data(), threads);
  }
  // The points left out of the grid or pyramid are evaluated after the others, from their own copy.
  std::vector<std::uint64_t> rest;
  for (std::size_t i = 0; i < count; ++i)
  {
    if (!admit[i])
    {
      rest.push_back(i);
      this->RestPositions.push_back({ points[3 * i], points[3 * i + 1], points[3 * i + 2] });
    }
  }
  if (multiresolution)
  {
    this->buildPyramid(points, normals, count, admit.data(), inputsCopied);
    if (this->BuildAborted)
    {
      return;
    }
    this->Order = this->Pyramid.takeIds();
  }
  else
  {
    this->Settings.evaluation = Evaluation::Exact;
    this->Grid.setThreads(threads);
    if (this->Settings.haveGridLattice)
    {
      this->Grid.buildOnLattice(points, unitNormals.data(), count, this->Settings.gridLattice, admit.data());
    }
    else
    {
      this->Grid.build(points, unitNormals.data(), count, exactGridCellSize(this->Settings.scales), admit.data());
    }
    UninitializedArray<double>().swap(unitNormals);
    if (inputsCopied)
    {
      inputsCopied();
    }
    const GridView& g = this->Grid.view();
    this->Order.assign(g.ids, g.ids + g.count);
  }
  this->Order.reserve(this->Order.size() + rest.size()); // exactly: an insertion's growth would double it
  this->Order.insert(this->Order.end(), rest.begin(), rest.end());
  this->chooseEvaluators();
}

ScaleSpaceEngine::~ScaleSpaceEngine() = default;
ScaleSpaceEngine::ScaleSpaceEngine(ScaleSpaceEngine&&) noexcept = default;
ScaleSpaceEngine& ScaleSpaceEngine::operator=(ScaleSpaceEngine&&) noexcept = default;

void ScaleSpaceEngine::chooseEvaluators()
{
  const EvaluatorBasis basis{ this->binning(), this->Settings.minNeighbors };
  const bool multiresolution = this->Settings.evaluation == Evaluation::Multiresolution;
  if (multiresolution && this->Settings.principalCurvatures)
  {
    this->Cpu = makeMultiresolutionCurvatureEvaluator(this->Pyramid.view(), this->CurvatureCells.data(), basis);
  }
  else if (multiresolution)
  {
    this->Cpu = makeMultiresolutionEvaluator(this->Pyramid.view(), basis);
  }
  else if (this->Settings.principalCurvatures)
  {
    this->Cpu = makeOnePassCurvatureEvaluator(this->Grid.view(), basis);
  }
  else if (this->Settings.method == EvaluationMethod::PerScale)
  {
    this->Cpu = makePerScaleEvaluator(this->Grid.view(), basis);
  }
  else
  {
    this->Cpu = makeOnePassEvaluator(this->Grid.view(), basis);
  }
  // The one place the device is chosen, or the CPU instead with the reason.
  if (this->Settings.backend == Backend::CPU)
  {
    return;
  }
  if (this->Settings.principalCurvatures)
  {
    this->DeviceRefusal = "the principal curvatures are computed on the CPU only";
    return;
  }
  if (!multiresolution && this->Settings.method != EvaluationMethod::OnePass)
  {
    this->DeviceRefusal = "the per-scale reference evaluation runs on the CPU only";
    return;
  }
  if (!cudaAvailability().usable)
  {
    this->DeviceRefusal = cudaAvailability().reason;
    return;
  }
  this->Device = makeCudaEvaluator(this->Grid.view(), multiresolution ? &this->Pyramid.view() : nullptr,
    this->Pyramid.nodeCount(), this->Pyramid.cellCount(), basis, this->Settings.deviceChunkLimit);
}

PyramidLayout ScaleSpaceEngine::pyramidLayout(
  const ScaleSpaceSettings& settings, const double* points, std::size_t count, const unsigned char* admit)
{
  MultiresolutionSettings m = settings.multiresolution;
  resolvePyramidFrame(m, points, count, admit);
  PyramidLayout layout =
    choosePyramidLayout(m.low, m.high, m.spacing, settings.scales.front(), settings.scales.back(), m.accuracy);
  layout.linearizedDistance = m.linearizedDistance;
  layout.singleWhereExact = m.singleWhereExact;
  layout.compactNormals = m.compactNormals;
  return layout;
}

void ScaleSpaceEngine::buildPyramid(const double* points, const double* normals, std::size_t count,
  const unsigned char* admit, const std::function<void()>& inputsCopied)
{
  const PyramidLayout layout = pyramidLayout(this->Settings, points, count, admit);
  this->BuildAborted =
    !this->Pyramid.build(points, normals, count, admit, layout, this->Settings.parallel, inputsCopied);
  if (!this->BuildAborted && this->Settings.principalCurvatures)
  {
    // The curvature set's cell sums, by the build's own rule (its threads; no progress of its own: a few percent of
    // the build).
    ParallelOptions threads;
    threads.threads = this->Settings.parallel.threads;
    this->CurvatureCells = summedCellsOf<ShapeOperatorMoments>(this->Pyramid.view(), threads);
  }
}

EngineFootprint ScaleSpaceEngine::footprint(
  const double* points, const double* normals, std::size_t count, const ScaleSpaceSettings& settings)
{
  const double n = static_cast<double>(count);
  UninitializedArray<unsigned char> admit(count);
  admitOrientedPoints(points, normals, count, admit.data(), settings.parallel.threads);
  std::size_t left = 0; // the points left out of the grid or pyramid, whose positions are kept apart
  for (std::size_t i = 0; i < count; ++i)
  {
    left += admit[i] ? 0 : 1;
  }
  // Throughout the build: the admit flags, the positions left out and their ids. Then the sorted copies (points,
  // normals, ids) and the sort's keys while the inputs are still read; after that, what stays.
  const double kept = n + static_cast<double>(left) * (sizeof(Vec3) + 8.0);
  const double sorted = n * (2.0 * sizeof(Vec3) + 8.0);
  if (settings.evaluation != Evaluation::Multiresolution || settings.scales.empty())
  {
    // The normalized normals the grid is built from; the grid's cell index, dense up to about 2 cells a point
    // (NeighborGrid::indexOccupiedCells), else smaller; Order, a copy of the grid's ids.
    const double index = n * 2.0 * 8.0 + 65537.0 * 8.0;
    const double built = kept + sorted + index + n * 8.0;
    return { kept + n * (sizeof(Vec3) + sizeof(KeyedIndex)) + sorted + index, built, built };
  }
  const PyramidLayout layout = pyramidLayout(settings, points, count, admit.data());
  const int threads = resolveThreadCount(settings.parallel.threads);
  const PyramidCounts counts = MultiresolutionCloud::count(points, admit.data(), count, layout, threads);
  // The coordinates (and compact normals) as floats where they are floats exactly (StoredPoints.h).
  const SortedStorage storage =
    MultiresolutionCloud::sortedStorage(points, normals, count, admit.data(), layout, threads, true);
  const double stored = n * storage.bytesPerPoint();
  // The sorted ids become Order. Each level's keys and starts while the next is made; the sort's keys until the
  // finest level's are made, then the nodes and the cells with their sums.
  const double nodes = static_cast<double>(counts.nodes);
  const double levels = std::max(n * sizeof(KeyedIndex),
    nodes * sizeof(PyramidNode) + static_cast<double>(counts.cells) * sizeof(PyramidCell));
  // The curvature set's cell sums, formed once the pyramid is built (counted in the build's phase too, above it).
  const double curvatureCells =
    settings.principalCurvatures ? static_cast<double>(counts.cells) * sizeof(CurvatureCell) : 0.0;
  // Running: the admit flags and the levels' scratch gone.
  const double cells = nodes * sizeof(PyramidNode) + static_cast<double>(counts.cells) * sizeof(PyramidCell) +
    static_cast<double>(counts.top) * 8.0 + curvatureCells;
  return { kept + n * sizeof(KeyedIndex) + stored, kept + stored + nodes * 2.0 * 8.0 + levels + curvatureCells,
    kept - n + stored + cells, n * storage.compactNormalsSaving() };
}

double ScaleSpaceEngine::memoryBytes() const
{
  return this->RestPositions.capacity() * sizeof(Vec3) + this->Order.capacity() * sizeof(std::uint32_t) +
    this->Grid.memoryBytes() + this->Pyramid.memoryBytes() +
    static_cast<double>(this->CurvatureCells.capacity() * sizeof(CurvatureCell));
}

ScaleBinning ScaleSpaceEngine::binning() const
{
  ScaleBinning b;
  b.scales = this->Settings.scales.data();
  b.squaredScales = this->SquaredScales.data();
  b.count = static_cast<int>(this->SquaredScales.size());
  b.table = this->BinTable.cells.data();
  b.tableSize = static_cast<int>(this->BinTable.cells.size());
  b.inverseCellWidth = this->BinTable.inverseCellWidth;
  return b;
}

bool ScaleSpaceEngine::run(
  ScaleSampleSink& sink, const std::vector<std::uint64_t>* ids, const ParallelOptions* parallel, RunReport* report) const
{
  if (this->BuildAborted)
  {
    return false;
  }
  const ParallelOptions& options = parallel ? *parallel : this->Settings.parallel;
  UninitializedArray<std::uint32_t> givenOrder;
  UninitializedArray<std::uint64_t> givenSlots;
  if (ids)
  {
    this->orderGivenIds(*ids, options.threads, givenOrder, givenSlots);
  }
  const RunPoints points = ids ? this->pointsOfRun(givenOrder.data(), ids->size(), givenSlots.data())
                               : this->pointsOfRun(this->Order.data(), this->Order.size(), nullptr);
  RunReport local;
  RunReport& r = report ? *report : local;
  r = RunReport();
  r.fallbackReason = this->DeviceRefusal;
  bool aborted = false;
  std::string failure;
  if (this->Device)
  {
    if (this->Device->run(points, sink, options, aborted, failure))
    {
      r.used = this->Device->backend();
      return true;
    }
    if (aborted)
    {
      return false;
    }
    r.fallbackReason = "CUDA failed (" + failure + ")";
  }
  r.used = Backend::CPU;
  return this->Cpu->run(points, sink, options, aborted, failure);
}

RunPoints ScaleSpaceEngine::pointsOfRun(
  const std::uint32_t* order, std::size_t count, const std::uint64_t* slots) const
{
  RunPoints points;
  points.order = order;
  points.count = count;
  points.slots = slots;
  points.sorted = this->sortedPoints();
  points.sortedCount = this->sortedCount();
  points.rest = this->RestPositions.data();
  return points;
}

StoredPoints ScaleSpaceEngine::sortedPoints() const
{
  if (this->Settings.evaluation == Evaluation::Multiresolution)
  {
    return this->Pyramid.view().points;
  }
  StoredPoints grid;
  grid.positions = this->Grid.view().points;
  grid.normals = this->Grid.view().normals;
  return grid;
}

std::size_t ScaleSpaceEngine::sortedCount() const
{
  return this->Settings.evaluation == Evaluation::Multiresolution ? this->Pyramid.view().count
                                                                   : this->Grid.view().count;
}

UninitializedArray<std::uint64_t> ScaleSpaceEngine::slotsOf(const std::vector<std::uint64_t>& ids, int threads) const
{
  UninitializedArray<std::uint64_t> slots(ids.size());
  ParallelOptions loop;
  loop.threads = threads;
  loop.chunk = 65536;
  if (ids.size() * kSampleFraction >= this->Count)
  {
    UninitializedArray<std::uint64_t> inverse(this->Count); // Order is a permutation of the ids below Count
    parallelFor(this->Order.size(), loop, [&](std::size_t b, std::size_t e, int) {
      for (std::size_t k = b; k < e; ++k)
      {
        inverse[this->Order[k]] = k;
      }
    });
    parallelFor(ids.size(), loop, [&](std::size_t b, std::size_t e, int) {
      for (std::size_t k = b; k < e; ++k)
      {
        slots[k] = inverse[ids[k]];
      }
    });
    return slots;
  }
  // A few ids: marked in a bitmap (Count bits), found in one pass over Order, then looked up by id.
  std::vector<std::uint64_t> marked((this->Count + 63) / 64, 0);
  for (std::uint64_t id : ids)
  {
    marked[id >> 6] |= std::uint64_t(1) << (id & 63);
  }
  std::vector<std::pair<std::uint64_t, std::uint64_t>> found; // (id, slot), each given id once
  for (std::size_t k = 0; k < this->Order.size(); ++k)
  {
    const std::uint64_t id = this->Order[k];
    if ((marked[id >> 6] >> (id & 63)) & 1)
    {
      found.emplace_back(id, k);
    }
  }
  std::sort(found.begin(), found.end());
  for (std::size_t k = 0; k < ids.size(); ++k)
  {
    slots[k] = std::lower_bound(found.begin(), found.end(), std::make_pair(ids[k], std::uint64_t(0)))->second;
  }
  return slots;
}

void ScaleSpaceEngine::orderGivenIds(const std::vector<std::uint64_t>& ids, int threads,
  UninitializedArray<std::uint32_t>& order, UninitializedArray<std::uint64_t>& slots) const
{
  UninitializedArray<std::uint64_t> given = this->slotsOf(ids, threads);
  const bool multiresolution = this->Settings.evaluation == Evaluation::Multiresolution;
  if (!multiresolution || ids.size() * kSampleFraction >= this->Count)
  {
    order.assign(ids.begin(), ids.end());
    slots = std::move(given);
    return;
  }
  // A sample of the points in pyramid order, so that consecutive walks find their cells in cache: the relative
  // sigma's 20,000 scattered points of a 10M-point cloud (2 threads) took 1.09 s in input order, 0.85 s in this
  // one. (Longer lists come in that order already: the owned points of a distributed piece.)
  const UninitializedArray<std::uint32_t> narrow(ids.begin(), ids.end()); // ids below Count
  const RunPoints points = this->pointsOfRun(narrow.data(), ids.size(), given.data());
  KeyedIndices byKey(ids.size());
  for (std::size_t k = 0; k < ids.size(); ++k)
  {
    byKey[k] = { this->Pyramid.finestKey(points.positionAt(k)), k };
  }
  sortByKey(byKey, threads);
  order.resize(ids.size());
  slots.resize(ids.size());
  for (std::size_t k = 0; k < ids.size(); ++k)
  {
    order[k] = ids[byKey[k].index];
    slots[k] = given[byKey[k].index];
  }
}

void ScaleSpaceEngine::evaluatePosition(const Vec3& p, std::vector<ScaleSample>& out) const
{
  const std::size_t S = this->Settings.scales.size();
  out.resize(S);
  if (!(isFinite(p.x) && isFinite(p.y) && isFinite(p.z)) || !this->Cpu)
  {
    for (std::size_t k = 0; k < S; ++k)
    {
      out[k] = invalidSample<double>(0.0);
    }
    return;
  }
  this->Cpu->evaluatePosition(p, out.data());
}

} // namespace gls
