#include "gls/TiledScaleSpace.h"

#include "gls/MultiresolutionCloud.h"
#include "gls/NeighborGrid.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gls
{
namespace
{

/// Passes a tile engine's samples on under the cloud's indices.
class CloudIndexSink : public ScaleSampleSink
{
public:
  CloudIndexSink(ScaleSampleSink& inner, const std::vector<std::uint64_t>& members)
    : Inner(inner)
    , Members(members)
  {
  }
  void consume(std::uint64_t local, const ScaleSample* samples, int thread) override
  {
    this->Inner.consume(this->Members[local], samples, thread);
  }
  void consumeCurvatures(std::uint64_t local, const PrincipalCurvatures* curvatures, int thread) override
  {
    this->Inner.consumeCurvatures(this->Members[local], curvatures, thread);
  }

private:
  ScaleSampleSink& Inner;
  const std::vector<std::uint64_t>& Members;
};

/// The share of a tile's progress its engine's build takes (the rest is its evaluation).
constexpr double kBuildShare = 0.1;

} // namespace

double ghostReach(const ScaleSpaceSettings& settings)
{
  if (settings.scales.empty())
  {
    return 0.0;
  }
  const double t = settings.scales.back();
  if (settings.evaluation != Evaluation::Multiresolution)
  {
    return t * (1.0 + 1e-9);
  }
  // A walk takes a cell whole when it lies within t of the walk's region (the cube of points that share the walk,
  // or for the linearized cells the far region around it) and its edge is at most Accuracy times that distance: its
  // points are at most t (1 + sqrt(3) Accuracy) from the region, plus the region's diagonal from p.
  const MultiresolutionSettings& m = settings.multiresolution;
  const PyramidLayout layout =
    choosePyramidLayout(m.low, m.high, m.spacing, settings.scales.front(), t, m.accuracy);
  double region = std::sqrt(3.0) * std::ldexp(layout.finestCellSize, layout.walkLevel);
  if (m.linearizedDistance > 0.0)
  {
    region = std::max(region, 2.0 * t / m.linearizedDistance); // far regions: half-diagonal below t / distance
  }
  return (t * (1.0 + std::sqrt(3.0) * m.accuracy) + region) * (1.0 + 1e-9);
}

TiledScaleSpace::TiledScaleSpace(
  const double* points, const double* normals, std::size_t count, std::size_t evaluated, ScaleSpaceSettings settings)
  : Points(points)
  , Normals(normals)
  , Count(count)
  , Evaluated(std::min(evaluated, count))
  , Settings(std::move(settings))
{
}

TiledScaleSpace::TiledScaleSpace(const double* points, const double* normals, std::size_t count,
  std::size_t evaluated, ScaleSpaceSettings settings, std::size_t tiles, const std::function<void()>& inputsCopied)
  : TiledScaleSpace(points, normals, count, evaluated, std::move(settings))
{
  this->Largest = count;
  if (tiles <= 1 || this->Settings.scales.empty())
  {
    this->Whole = std::make_unique<ScaleSpaceEngine>(points, normals, count, this->Settings, inputsCopied);
    this->Points = this->Normals = nullptr; // read by tiles only (and perhaps freed by now)
    if (this->Evaluated < count)
    {
      for (std::uint64_t id : this->Whole->evaluationOrder())
      {
        if (id < this->Evaluated)
        {
          this->WholeOwnedOrder.push_back(id);
        }
      }
    }
    return;
  }
  this->layOnTheWholeCloud();
  this->Tiles = SpatialTiles::plan(points, this->Evaluated, tiles);
  this->Largest = 0;
  for (std::size_t size : this->tileSizes())
  {
    this->Largest = std::max(this->Largest, size);
  }
}

TiledScaleSpace::TiledScaleSpace(const double* points, const double* normals, std::size_t count,
  std::size_t evaluated, ScaleSpaceSettings settings, const std::vector<std::uint64_t>& selected)
  : TiledScaleSpace(points, normals, count, evaluated, std::move(settings))
{
  this->AroundSelected = true;
  for (std::uint64_t id : selected)
  {
    if (id < this->Evaluated)
    {
      this->Selected.push_back(id);
    }
  }
  std::sort(this->Selected.begin(), this->Selected.end());
  this->Selected.erase(std::unique(this->Selected.begin(), this->Selected.end()), this->Selected.end());
  if (this->Selected.empty() || this->Settings.scales.empty())
  {
    this->Selected.clear();
    return; // nothing to evaluate
  }
  this->layOnTheWholeCloud();
  std::vector<Vec3> centres;
  for (std::uint64_t id : this->Selected)
  {
    centres.push_back({ points[3 * id], points[3 * id + 1], points[3 * id + 2] });
  }
  const double reach2 = this->Reach * this->Reach;
  this->collect(
    [&](std::size_t i) -> int {
      if (std::binary_search(this->Selected.begin(), this->Selected.end(), static_cast<std::uint64_t>(i)))
      {
        return 1;
      }
      if (!this->Admit[i])
      {
        return 0;
      }
      const Vec3 p{ points[3 * i], points[3 * i + 1], points[3 * i + 2] };
      for (const Vec3& c : centres)
      {
        if (squaredNorm(p - c) <= reach2) // false for a NaN coordinate, like the tiles' boxes
        {
          return 2;
        }
      }
      return 0;
    },
    this->SelectedMembers, this->SelectedOwn);
  this->Largest = this->SelectedMembers.size();
}

void TiledScaleSpace::layOnTheWholeCloud()
{
  // What each part's engine would otherwise take from its own points: the whole cloud's box, spacing and lattice.
  this->Admit.resize(this->Count);
  admitOrientedPoints(this->Points, this->Normals, this->Count, this->Admit.data(), this->Settings.parallel.threads);
  if (this->Settings.evaluation == Evaluation::Multiresolution)
  {
    resolvePyramidFrame(this->Settings.multiresolution, this->Points, this->Count, this->Admit.data());
  }
  else
  {
    this->Settings.gridLattice =
      exactGridLattice(this->Points, this->Count, this->Admit.data(), this->Settings.scales);
    this->Settings.haveGridLattice = true;
  }
  this->Reach = ghostReach(this->Settings);
}

int TiledScaleSpace::membership(std::size_t k, std::size_t i) const
{
  const double* p = this->Points + 3 * i;
  if (i < this->Evaluated && this->Tiles.holds(k, p))
  {
    return 1;
  }
  return this->Admit[i] && this->Tiles.near(k, p, this->Reach) ? 2 : 0;
}

std::vector<std::size_t> TiledScaleSpace::tileSizes() const
{
  // A point can belong only to the box that holds it and, when admitted, the boxes near it: those are asked.
  const int threads = resolveThreadCount(this->Settings.parallel.threads);
  const std::size_t T = this->Tiles.count();
  std::vector<std::vector<std::size_t>> counts(static_cast<std::size_t>(threads), std::vector<std::size_t>(T, 0));
  ParallelOptions options;
  options.threads = threads;
  options.chunk = 65536;
  parallelFor(this->Count, options, [&](std::size_t begin, std::size_t end, int thread) {
    std::vector<std::size_t>& c = counts[static_cast<std::size_t>(thread)];
    for (std::size_t i = begin; i < end; ++i)
    {
      const double* p = this->Points + 3 * i;
      const std::size_t box = this->Tiles.tileOf(p);
      c[box] += this->membership(box, i) != 0 ? 1 : 0;
      if (this->Admit[i])
      {
        this->Tiles.forEachNear(p, this->Reach, [&](std::size_t k) {
          c[k] += k != box && this->membership(k, i) != 0 ? 1 : 0;
        });
      }
    }
  });
  std::vector<std::size_t> sizes(T, 0);
  for (const std::vector<std::size_t>& c : counts)
  {
    for (std::size_t k = 0; k < T; ++k)
    {
      sizes[k] += c[k];
    }
  }
  return sizes;
}

void TiledScaleSpace::members(std::size_t k, std::vector<std::uint64_t>& members, std::vector<unsigned char>& own) const
{
  this->collect([&](std::size_t i) { return this->membership(k, i); }, members, own);
}

template <class Kind>
void TiledScaleSpace::collect(
  const Kind& kind, std::vector<std::uint64_t>& members, std::vector<unsigned char>& own) const
{
  // Counted per slice, then written per slice: the cloud's order whatever the thread count.
  const int threads = resolveThreadCount(this->Settings.parallel.threads);
  const std::size_t slices = static_cast<std::size_t>(threads) * 4;
  const auto sliceBegin = [this, slices](std::size_t s) { return this->Count * s / slices; };
  std::vector<std::size_t> first(slices + 1, 0);
  ParallelOptions bySlice;
  bySlice.threads = threads;
  bySlice.chunk = 1;
  parallelFor(slices, bySlice, [&](std::size_t s, std::size_t, int) {
    std::size_t n = 0;
    for (std::size_t i = sliceBegin(s); i < sliceBegin(s + 1); ++i)
    {
      n += kind(i) != 0 ? 1 : 0;
    }
    first[s + 1] = n;
  });
  for (std::size_t s = 0; s < slices; ++s)
  {
    first[s + 1] += first[s];
  }
  members.resize(first[slices]);
  own.resize(first[slices]);
  parallelFor(slices, bySlice, [&](std::size_t s, std::size_t, int) {
    std::size_t j = first[s];
    for (std::size_t i = sliceBegin(s); i < sliceBegin(s + 1); ++i)
    {
      const int c = kind(i);
      if (c != 0)
      {
        members[j] = i;
        own[j++] = c == 1 ? 1 : 0;
      }
    }
  });
}

bool TiledScaleSpace::run(ScaleSampleSink& sink, const std::vector<std::uint64_t>* ids,
  const ParallelOptions& parallel, RunReport& report) const
{
  report = RunReport();
  if (this->Whole)
  {
    const std::vector<std::uint64_t>* order = ids || this->WholeOwnedOrder.empty() ? ids : &this->WholeOwnedOrder;
    return this->Whole->run(sink, order, &parallel, &report);
  }
  if (this->AroundSelected)
  {
    std::vector<std::uint64_t> requested;
    for (std::uint64_t id : ids ? *ids : this->Selected)
    {
      if (std::binary_search(this->Selected.begin(), this->Selected.end(), id))
      {
        requested.push_back(id);
      }
    }
    return this->runMembers(
      this->SelectedMembers, this->SelectedOwn, &requested, sink, parallel, report, true);
  }
  const double tiles = static_cast<double>(this->Tiles.count());
  for (std::size_t k = 0; k < this->Tiles.count(); ++k)
  {
    const ParallelOptions stage = progressStage(parallel, k / tiles, (k + 1) / tiles);
    if (!this->runTile(k, sink, ids, stage, report))
    {
      return false;
    }
  }
  return true;
}

bool TiledScaleSpace::runTile(std::size_t k, ScaleSampleSink& sink, const std::vector<std::uint64_t>* ids,
  const ParallelOptions& parallel, RunReport& report) const
{
  std::vector<std::uint64_t> requested; // the requested points this tile holds
  if (ids)
  {
    for (std::uint64_t id : *ids)
    {
      if (id < this->Evaluated && this->Tiles.holds(k, this->Points + 3 * id))
      {
        requested.push_back(id);
      }
    }
    if (requested.empty())
    {
      return !parallel.progress || !parallel.progress(1.0);
    }
  }
  std::vector<std::uint64_t> members;
  std::vector<unsigned char> own;
  this->members(k, members, own);
  return this->runMembers(members, own, ids ? &requested : nullptr, sink, parallel, report, k == 0);
}

bool TiledScaleSpace::runMembers(const std::vector<std::uint64_t>& members, const std::vector<unsigned char>& own,
  const std::vector<std::uint64_t>* requested, ScaleSampleSink& sink, const ParallelOptions& parallel,
  RunReport& report, bool first) const
{
  // The evaluation list, in the engine's indices: the requested points, or all the own points.
  std::vector<std::uint64_t> local;
  if (requested)
  {
    if (requested->empty())
    {
      return !parallel.progress || !parallel.progress(1.0);
    }
    for (std::uint64_t id : *requested)
    {
      local.push_back(
        static_cast<std::uint64_t>(std::lower_bound(members.begin(), members.end(), id) - members.begin()));
    }
  }
  std::unique_ptr<ScaleSpaceEngine> engine;
  {
    UninitializedArray<double> points(3 * members.size()), normals(3 * members.size());
    for (std::size_t j = 0; j < members.size(); ++j)
    {
      std::copy(this->Points + 3 * members[j], this->Points + 3 * members[j] + 3, points.data() + 3 * j);
      std::copy(this->Normals + 3 * members[j], this->Normals + 3 * members[j] + 3, normals.data() + 3 * j);
    }
    ScaleSpaceSettings settings = this->Settings;
    settings.parallel = progressStage(parallel, 0.0, kBuildShare);
    engine = std::make_unique<ScaleSpaceEngine>(
      points.data(), normals.data(), members.size(), std::move(settings), [&points, &normals] {
        UninitializedArray<double>().swap(points); // the engine holds its sorted copies: freed before its cells
        UninitializedArray<double>().swap(normals);
      });
  }
  if (engine->buildAborted())
  {
    return false;
  }
  if (!requested)
  {
    for (std::uint64_t j : engine->evaluationOrder())
    {
      if (own[j])
      {
        local.push_back(j);
      }
    }
  }
  CloudIndexSink toCloud(sink, members);
  const ParallelOptions evaluation = progressStage(parallel, kBuildShare, 1.0);
  RunReport partReport;
  const bool completed =
    engine->run(toCloud, &local, &evaluation, &partReport);
  if (first || partReport.used != Backend::CUDA)
  {
    report = partReport; // a fallback on any part is reported
  }
  return completed;
}

} // namespace gls
