#include "vtkGLSScaleFilterBase.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSRun.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"

#include "gls/Evaluation.h"
#include "gls/ScaleSampling.h"
#include "gls/TiledScaleSpace.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>

namespace
{

/// The coverage keeps one row of neighbour counts every kCoverageStride points, or fewer: at most about kCoverageRows
/// rows (a deterministic sample of the ids, for a median; at 10^8 points every 61st point's rows took 262 MB, held
/// three times over at the end of the pass: the rows, their concatenation and its gathered copy).
constexpr std::uint64_t kCoverageStride = 61;
constexpr double kCoverageRows = 20000.0;

/// The ids whose rows the coverage of a run of `points` points keeps: the multiples of this.
std::uint64_t CoverageStride(std::size_t points)
{
  return std::max(kCoverageStride, static_cast<std::uint64_t>(std::ceil(static_cast<double>(points) / kCoverageRows)));
}

/// What the rows of a run of `points` points cost at most (bytes per scale): the threads' rows and their concatenation
/// (each at most doubled by their vectors' growth), and its gathered copy.
double CoverageBytesPerScale(std::size_t points)
{
  const double rows = std::ceil(static_cast<double>(points) / static_cast<double>(CoverageStride(points))) + 1.0;
  return 5.0 * sizeof(double) * rows;
}

/// Forwards the samples and keeps, per scale, how many were valid, and the neighbour counts of the points whose id is
/// a multiple of the stride (a deterministic sample, for a median).
class CoverageSink : public gls::ScaleSampleSink
{
public:
  CoverageSink(gls::ScaleSampleSink& inner, std::size_t scales, int threads, std::uint64_t stride)
    : Inner(inner)
    , S(scales)
    , Stride(stride)
    , Valid(static_cast<std::size_t>(threads), std::vector<double>(scales, 0.0))
    , Points(static_cast<std::size_t>(threads), 0.0)
    , Neighbors(static_cast<std::size_t>(threads))
  {
  }
  void consumeCurvatures(std::uint64_t id, const gls::PrincipalCurvatures* c, int thread) override
  {
    this->Inner.consumeCurvatures(id, c, thread);
  }
  void consume(std::uint64_t id, const gls::ScaleSample* s, int thread) override
  {
    this->Inner.consume(id, s, thread);
    const std::size_t t = static_cast<std::size_t>(thread);
    this->Points[t] += 1.0;
    for (std::size_t k = 0; k < this->S; ++k)
    {
      this->Valid[t][k] += s[k].valid ? 1.0 : 0.0;
    }
    if (id % this->Stride == 0)
    {
      for (std::size_t k = 0; k < this->S; ++k)
      {
        this->Neighbors[t].push_back(s[k].neighbors);
      }
    }
  }

  gls::ScaleSampleSink& Inner;
  std::size_t S;
  std::uint64_t Stride;
  std::vector<std::vector<double>> Valid;
  std::vector<double> Points;
  std::vector<std::vector<double>> Neighbors; ///< rows of S counts
};

}

vtkGLSScaleFilterBase::vtkGLSScaleFilterBase()
  : MinScale(0.008)
  , MaxScale(0.08)
  , NumberOfScales(20)
  , ScaleSampling(QUADRATIC)
  , Backend(BACKEND_AUTO)
  , Evaluation(EVALUATION_AUTO)
  , Accuracy(gls::kDefaultAccuracy)
{
}

vtkGLSScaleFilterBase::~vtkGLSScaleFilterBase() = default;

void vtkGLSScaleFilterBase::AddScale(double scale)
{
  this->ExplicitScales.push_back(scale);
  this->Modified();
}

void vtkGLSScaleFilterBase::RemoveAllScales()
{
  if (!this->ExplicitScales.empty())
  {
    this->ExplicitScales.clear();
    this->Modified();
  }
}

int vtkGLSScaleFilterBase::Execute(vtkGLSRun& run)
{
  this->LastBackendUsed.clear();
  this->LastEvaluationUsed.clear();
  this->LastTileCount = 0;
  if (!this->CheckFitParameters() || !this->CheckParameters(run) ||
    !this->PrepareSamples(run, this->GetSampleRequest(run)))
  {
    return FAILED;
  }
  const int outcome = this->ComputeOutputs(run);
  this->LastBackendUsed = run.BackendUsed;
  this->LastEvaluationUsed = run.EvaluationUsed;
  if (outcome == COMPLETED && run.Output)
  {
    WriteScales(run.Output->GetFieldData(), run.Scales);
    WriteRunFieldData(run, run.Output->GetFieldData());
  }
  return outcome;
}

bool vtkGLSScaleFilterBase::CheckParameters(vtkGLSRun&)
{
  return true;
}

bool vtkGLSScaleFilterBase::ResolveScales(vtkGLSRun& run)
{
  run.Scales = this->ScaleList(run.Diagonal, this->ScaleSampling);
  return !run.Scales.empty();
}

bool vtkGLSScaleFilterBase::GatherFitCloud(vtkGLSRun& run)
{
  return this->GatherNormals(run);
}

bool vtkGLSScaleFilterBase::PrepareSamples(vtkGLSRun& run, const SampleRequest& request)
{
  bool ok = true;
  if (request.MayReuseInput && this->TakeStoredSamples(run, request, ok))
  {
    return ok;
  }
  return this->PrepareFit(run, request);
}

double vtkGLSScaleFilterBase::RunBytes(const vtkGLSRun& run, const SampleRequest& request, double bytes, double scales)
{
  // Every large allocation of the run, counted before any is made: per (point, scale), per point and per scale.
  return bytes + static_cast<double>(run.Input->GetNumberOfPoints()) * request.BytesPerPoint +
    scales * request.BytesPerScale;
}

bool vtkGLSScaleFilterBase::TakeStoredSamples(vtkGLSRun& run, const SampleRequest& request, bool& ok)
{
  const vtkGLSDistributedCloud& dist = run.Distributed;
  vtkPointSet* input = run.Input;
  const vtkIdType n = input->GetNumberOfPoints();
  const bool emptyPiece = dist.IsParallel() && n == 0;
  // Every rank must take the same path: stored arrays only when every piece has them (an empty piece goes along).
  const auto everywhere = [&](bool local) {
    return dist.AllTrue(local || emptyPiece) && (!dist.IsParallel() || dist.Max(local ? 1.0 : 0.0) > 0.5);
  };
  const std::vector<double> stored = ReadStoredScales(input->GetFieldData());
  const double S = static_cast<double>(stored.size());
  if (request.VariationWillDo)
  {
    vtkDataArray* nu = input->GetPointData()->GetArray(vtkGLSArrayNames::Variation);
    const bool haveNu = !stored.empty() && nu && nu->GetNumberOfComponents() == static_cast<int>(stored.size()) &&
      nu->GetNumberOfTuples() == n;
    if (everywhere(haveNu))
    {
      run.Scales = stored;
      run.StoredVariation = haveNu ? nu : nullptr;
      run.Samples = vtkGLSSampleSource::Empty();
      ok = true;
      return true;
    }
  }
  std::unique_ptr<vtkGLSSampleSource> samples = stored.empty()
    ? nullptr
    : vtkGLSSampleSource::Stored(
        input, stored.size(), request.Descriptors, request.Derivatives, request.PrincipalCurvatures);
  if (!everywhere(samples != nullptr))
  {
    return false;
  }
  run.Scales = stored;
  run.Samples = samples ? std::move(samples) : vtkGLSSampleSource::Empty();
  ok = this->AgreeToContinue(run,
    this->CheckMemoryBudget(RunBytes(run, request, static_cast<double>(n) * S * request.BytesPerPointScale, S),
      request.What, request.Advice));
  return true;
}

bool vtkGLSScaleFilterBase::PrepareFit(vtkGLSRun& run, const SampleRequest& request)
{
  // A fit of the points and normals at this filter's scales: the outputs must fit in the budget; the engine too, or
  // else its largest tile (ChooseTiles, once the cloud is complete).
  const vtkGLSDistributedCloud& dist = run.Distributed;
  bool ok = this->ResolveScales(run);
  const std::size_t owned = run.Cloud.Owned;
  if (static_cast<std::uint64_t>(run.Input->GetNumberOfPoints()) > gls::kMaxEnginePoints)
  {
    vtkErrorMacro("The input has " << run.Input->GetNumberOfPoints() << " points: a fit takes at most "
                                   << gls::kMaxEnginePoints << ". Fit parts of the cloud.");
    return this->AgreeToContinue(run, false);
  }
  const double S = static_cast<double>(run.Scales.size());
  const double outputs = static_cast<double>(owned) * S * request.BytesPerPointScale +
    S * CoverageBytesPerScale(static_cast<std::size_t>(run.Input->GetNumberOfPoints()));
  const double fixed = RunBytes(run, request, outputs, S);
  ok = ok && this->CheckMemoryBudget(fixed, request.What, request.Advice) && this->GatherFitCloud(run);
  if (!this->AgreeToContinue(run, ok))
  {
    return false;
  }
  this->WarnAboutNormalLengths(run, run.Cloud.Normals, run.NormalsName.c_str());
  this->ResolveMinimumNeighbors(run);
  // Distributed: the other pieces' points within the largest scale of this piece join the fit after the owned
  // points; only the owned ones are evaluated.
  if (dist.IsParallel() && !this->AddGhosts(run, this->GhostReach(run)))
  {
    return false;
  }
  this->MergeCoincidentPoints(run);
  gls::ScaleSpaceSettings settings;
  settings.scales = run.Scales;
  settings.minNeighbors = run.MinimumNeighbors;
  settings.parallel.threads = this->NumberOfThreads;
  settings.backend = static_cast<gls::Backend>(this->Backend);
  settings.principalCurvatures = request.PrincipalCurvatures;
  // The pyramid's build reports its progress in the first 2% (the feed's own progress follows) and stops when
  // aborted.
  settings.parallel.progress = [this](double f) { return this->ReportProgress(f, 0.0, 0.02); };
  this->ChooseEvaluation(run, settings);
  // A few selected points (every piece agrees): a fit around them, whatever the cloud's size.
  if (dist.AllTrue(request.Only && request.Only->size() <= gls::TiledScaleSpace::kMaxSelected))
  {
    run.Samples = vtkGLSSampleSource::FitAround(run.Cloud, settings, *request.Only);
    run.TilesUsed = 1;
    this->LastTileCount = 1;
    this->Heartbeat();
    return true;
  }
  std::unique_ptr<vtkGLSSampleSource> tiled;
  if (!this->AgreeToContinue(run, this->ChooseTiles(run, settings, fixed, request, tiled)))
  {
    return false;
  }
  // One engine frees the cloud's coordinates once it holds its own copies; tiles read them as they are built.
  run.Samples = tiled ? std::move(tiled) : vtkGLSSampleSource::FitWholeReleasing(run.Cloud, settings);
  run.TilesUsed = static_cast<long long>(run.Samples->TileCount());
  this->LastTileCount = static_cast<int>(run.TilesUsed);
  this->Heartbeat();
  return true;
}

bool vtkGLSScaleFilterBase::ChooseTiles(vtkGLSRun& run, gls::ScaleSpaceSettings& settings, double fixed,
  const SampleRequest& request, std::unique_ptr<vtkGLSSampleSource>& tiled)
{
  const std::size_t S = settings.scales.size();
  const int threads = gls::resolveThreadCount(this->NumberOfThreads);
  const double budget = this->MemoryBudgetBytes();
  // The cloud's coordinates: one engine over the whole cloud frees them once it holds its copies
  // (FitWholeReleasing); tiles read them while they are built.
  const double cloud = static_cast<double>(run.Cloud.Size()) * vtkGLSCloud::BytesPerPoint;
  tiled.reset();
  if (run.Cloud.Owned == 0)
  {
    return true;
  }
  gls::EngineFootprint engine = vtkGLSSampleSource::EngineBytes(run.Cloud, settings);
  // One engine: its build (the outputs are made once it is built), then the engine as it runs beside the outputs and
  // the threads' scratch.
  const auto untiled = [&](const gls::EngineFootprint& e) {
    const std::size_t n = run.Cloud.Size();
    return e.withOutputs(cloud, fixed + vtkGLSSampleSource::EngineShareBytes(0.0, n, n, S, threads));
  };
  if (untiled(engine) <= budget)
  {
    return true;
  }
  // The pyramid's normals kept as given (floats) and normalized when read: the same samples, 12 bytes a point less,
  // a longer pass (StoredPoints.h). Tiles, if still needed, keep them so too.
  if (engine.compactNormalsSaving > 0.0)
  {
    engine = engine.withCompactNormals();
    settings.multiresolution.compactNormals = true;
    run.CompactNormals = true;
    if (untiled(engine) <= budget)
    {
      return true;
    }
  }
  const double whole = engine.bytes(0.0);
  // Twice the tiles until the largest (with its ghost band) fits, while cutting still makes tiles clearly smaller.
  double need = 0.0;
  std::size_t previous = run.Cloud.Size();
  for (std::size_t want = 2; want <= kMaximumTiles; want *= 2)
  {
    gls::ScaleSpaceSettings planning = settings;
    planning.parallel.progress = nullptr;
    tiled = vtkGLSSampleSource::Fit(run.Cloud, planning, want);
    const std::size_t largest = tiled->LargestTile();
    need = fixed + cloud + vtkGLSSampleSource::EngineShareBytes(whole, run.Cloud.Size(), largest, S, threads) +
      static_cast<double>(largest) * gls::TiledScaleSpace::kBytesPerTilePoint;
    if (need <= budget)
    {
      return true;
    }
    if (static_cast<double>(largest) > kTileShrink * static_cast<double>(previous) || tiled->TileCount() < want)
    {
      break; // the tiles' ghost bands (the largest scale) or identical points keep them about this large
    }
    previous = largest;
  }
  tiled.reset();
  std::ostringstream advice;
  advice << "Even cut into spatial tiles (each with the points within the largest scale of it) the fit does not fit. "
         << request.Advice << " Or raise MemoryBudget, or use smaller scales.";
  return this->CheckMemoryBudget(need, request.What, advice.str().c_str());
}

double vtkGLSScaleFilterBase::GhostReach(const vtkGLSRun& run) const
{
  // Decided before the evaluation is (Auto may take either): the multi-resolution band, the wider, unless Exact.
  gls::ScaleSpaceSettings settings;
  settings.scales = run.Scales;
  settings.evaluation =
    this->Evaluation == EVALUATION_EXACT ? gls::Evaluation::Exact : gls::Evaluation::Multiresolution;
  this->LayOutPyramid(run, settings.multiresolution);
  return gls::ghostReach(settings);
}

void vtkGLSScaleFilterBase::LayOutPyramid(const vtkGLSRun& run, gls::MultiresolutionSettings& m) const
{
  // The layout from global facts only (the whole input's box and point count), so that every piece of a
  // distributed run lays its pyramid out like the serial run.
  m.accuracy = this->Accuracy;
  m.haveBounds = run.HasFinitePoints;
  for (int a = 0; a < 3; ++a) // in the cloud's coordinates (from its anchor)
  {
    m.low[a] = run.Bounds[2 * a] - run.Cloud.Anchor[a];
    m.high[a] = run.Bounds[2 * a + 1] - run.Cloud.Anchor[a];
  }
  const double points = run.Distributed.Sum(static_cast<double>(run.Input->GetNumberOfPoints()));
  m.spacing = gls::surfaceSpacingOfBox(m.low, m.high, static_cast<std::size_t>(points));
}

void vtkGLSScaleFilterBase::ChooseEvaluation(vtkGLSRun& run, gls::ScaleSpaceSettings& settings)
{
  const vtkGLSDistributedCloud& dist = run.Distributed;
  const double t = run.Scales.back();
  gls::BallCountEstimate estimate; // only Auto needs it (every rank takes the same branch)
  const bool automatic = this->Evaluation == EVALUATION_AUTO;
  if (automatic)
  {
    estimate = gls::estimateBallCount(run.Cloud.Points.data(), run.Cloud.Size(), run.Cloud.Owned, t);
    estimate.neighbors = dist.Sum(estimate.neighbors);
    estimate.samples = dist.Sum(estimate.samples);
  }
  const bool cells = this->Evaluation == EVALUATION_MULTIRESOLUTION ||
    (automatic && estimate.mean() > gls::kExactNeighborLimit);
  settings.evaluation = cells ? gls::Evaluation::Multiresolution : gls::Evaluation::Exact;
  run.EvaluationUsed = cells ? "Multiresolution" : "Exact";
  run.AccuracyUsed = this->Accuracy;
  if (cells)
  {
    this->LayOutPyramid(run, settings.multiresolution);
  }
}

bool vtkGLSScaleFilterBase::FeedSamples(vtkGLSRun& run, gls::ScaleSampleSink& sink,
  const std::vector<std::uint64_t>* ids, double progressBegin, double progressEnd)
{
  gls::ParallelOptions parallel;
  parallel.threads = this->NumberOfThreads;
  parallel.progress = [this, progressBegin, progressEnd](double f) {
    return this->ReportProgress(f, progressBegin, progressEnd);
  };
  gls::RunReport report;
  const int threads = gls::resolveThreadCount(this->NumberOfThreads);
  const bool diagnose = !ids && run.Samples->RunsFits(); // every point of a fit: say when most fits are NaN
  CoverageSink coverage(
    sink, run.Scales.size(), threads, CoverageStride(static_cast<std::size_t>(run.Input->GetNumberOfPoints())));
  const bool completed = run.Samples->Feed(
    diagnose ? coverage : sink, ids, parallel, report);
  if (!ids && completed)
  {
    this->WarnAboutUndefinedScales(run, diagnose ? &coverage : nullptr);
  }
  if (run.Samples->RunsFits())
  {
    run.BackendUsed = gls::backendName(report.used);
    if (this->Backend == BACKEND_CUDA && report.used != gls::Backend::CUDA && !this->WarnedAboutBackend)
    {
      this->WarnedAboutBackend = true;
      vtkWarningMacro("Backend CUDA requested but not available (" << report.fallbackReason
                                                                    << "); computing on the CPU instead.");
    }
  }
  return completed;
}

void vtkGLSScaleFilterBase::WarnAboutUndefinedScales(const vtkGLSRun& run, const gls::ScaleSampleSink* diagnosis)
{
  // Collective: every rank of a fit reaches this after feeding all its points (an empty piece with no sink too).
  const vtkGLSDistributedCloud& dist = run.Distributed;
  const std::size_t S = run.Scales.size();
  const auto* coverage = static_cast<const CoverageSink*>(diagnosis);
  double points = 0.0;
  std::vector<double> valid(S, 0.0), rows;
  if (coverage)
  {
    for (std::size_t t = 0; t < coverage->Points.size(); ++t)
    {
      points += coverage->Points[t];
      for (std::size_t k = 0; k < S; ++k)
      {
        valid[k] += coverage->Valid[t][k];
      }
      rows.insert(rows.end(), coverage->Neighbors[t].begin(), coverage->Neighbors[t].end());
    }
  }
  if (!dist.AllTrue(true) || S == 0)
  {
    return;
  }
  points = dist.Sum(points);
  for (double& v : valid)
  {
    v = dist.Sum(v);
  }
  std::vector<double> all;
  std::vector<long long> counts;
  if (!dist.GatherRows(rows, static_cast<int>(S), 0, all, counts) || dist.GetRank() != 0 || !(points > 0.0))
  {
    return;
  }
  std::vector<std::size_t> undefined;
  for (std::size_t k = 0; k < S; ++k)
  {
    if (valid[k] < 0.5 * points)
    {
      undefined.push_back(k);
    }
  }
  if (undefined.empty())
  {
    return;
  }
  // The median neighbour count over the sampled points, at the undefined scales.
  std::vector<double> neighbors;
  for (std::size_t r = 0; r < all.size() / S; ++r)
  {
    for (std::size_t k : undefined)
    {
      neighbors.push_back(all[r * S + k]);
    }
  }
  double median = 0.0;
  if (!neighbors.empty())
  {
    std::nth_element(neighbors.begin(), neighbors.begin() + static_cast<long>(neighbors.size() / 2), neighbors.end());
    median = neighbors[neighbors.size() / 2];
  }
  std::ostringstream range;
  range << run.Scales[undefined.front()];
  if (undefined.size() > 1)
  {
    range << " to " << run.Scales[undefined.back()];
  }
  vtkWarningMacro("At " << undefined.size() << " of the " << S << " scales (t = " << range.str()
                        << ") most fits are undefined (NaN): the median neighbour count there is " << median
                        << ", below MinimumNeighbors " << run.MinimumNeighbors
                        << ". Use larger scales (MinScale, Scales) or a denser cloud.");
}

std::vector<double> vtkGLSScaleFilterBase::ComputeAbsoluteScales(vtkPointSet* input)
{
  const vtkGLSDistributedCloud serial(nullptr);
  const vtkIdType n = input->GetNumberOfPoints();
  std::vector<double> xyz(3 * static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    input->GetPoint(i, &xyz[3 * i]);
  }
  std::vector<std::uint64_t> stray;
  BlankStrayPoints(serial, xyz, stray); // as a run does
  double b[6];
  double diagonal = 0.0;
  if (serial.FiniteBounds(xyz.data(), static_cast<std::size_t>(n), b))
  {
    diagonal = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
  }
  return this->ScaleList(diagonal, this->ScaleSampling);
}

std::vector<double> vtkGLSScaleFilterBase::ScaleList(double diagonal, int sampling)
{
  const bool relative = this->ScaleUnits == RELATIVE_TO_DIAGONAL;
  if (relative && !(diagonal > 0.0))
  {
    vtkErrorMacro("Invalid scales: they are relative to the bounding-box diagonal, and it is zero (all points with "
                  "finite coordinates coincide, or there are none): set ScaleUnits to ABSOLUTE.");
    return {};
  }
  const auto absolute = [&](double value) { return relative ? value * diagonal : value; };
  std::vector<double> scales;
  if (!this->ExplicitScales.empty())
  {
    for (double s : this->ExplicitScales)
    {
      scales.push_back(absolute(s));
    }
    const std::string why = gls::checkScaleList(scales);
    if (!why.empty())
    {
      vtkErrorMacro("Invalid scales: " << why << ".");
      return {};
    }
    return scales;
  }
  const double tmin = absolute(this->MinScale);
  const double tmax = absolute(this->MaxScale);
  std::string why = gls::checkScaleRange(this->MinScale, this->MaxScale, this->NumberOfScales);
  if (why.empty())
  {
    why = gls::checkScaleRange(tmin, tmax, this->NumberOfScales);
  }
  if (!why.empty())
  {
    vtkErrorMacro("Invalid scales: " << why
                                     << (relative ? " (scales are relative to the bounding-box diagonal)." : "."));
    return {};
  }
  return gls::sampleScales(tmin, tmax, this->NumberOfScales, static_cast<gls::ScaleSampling>(sampling));
}

void vtkGLSScaleFilterBase::WriteScales(vtkFieldData* fd, const std::vector<double>& scales)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(vtkGLSArrayNames::Scales);
  a->SetNumberOfTuples(static_cast<vtkIdType>(scales.size()));
  for (std::size_t k = 0; k < scales.size(); ++k)
  {
    a->SetValue(static_cast<vtkIdType>(k), scales[k]);
  }
  fd->AddArray(a);
}

std::vector<double> vtkGLSScaleFilterBase::ReadStoredScales(vtkFieldData* fd)
{
  std::vector<double> scales;
  vtkDataArray* a = fd ? fd->GetArray(vtkGLSArrayNames::Scales) : nullptr;
  if (!a || a->GetNumberOfComponents() != 1)
  {
    return scales;
  }
  for (vtkIdType k = 0; k < a->GetNumberOfTuples(); ++k)
  {
    scales.push_back(a->GetComponent(k, 0));
  }
  if (!gls::checkScaleList(scales).empty())
  {
    scales.clear();
  }
  return scales;
}

void vtkGLSScaleFilterBase::NameScaleComponents(vtkDataArray* array, const std::vector<double>& scales, int perScale)
{
  static const char* axes[] = { " x", " y", " z" };
  for (std::size_t k = 0; k < scales.size(); ++k)
  {
    for (int c = 0; c < perScale; ++c)
    {
      char name[64];
      std::snprintf(name, sizeof(name), "t=%.4g%s", scales[k], perScale == 3 ? axes[c] : "");
      array->SetComponentName(static_cast<vtkIdType>(k) * perScale + c, name);
    }
  }
}

void vtkGLSScaleFilterBase::DescribeSettings(std::vector<SettingRange>& settings)
{
  this->Superclass::DescribeSettings(settings);
  settings.push_back({ "ScaleSampling", static_cast<double>(this->ScaleSampling), static_cast<double>(LINEAR), static_cast<double>(LOGARITHMIC) });
  settings.push_back({ "Backend", static_cast<double>(this->Backend), static_cast<double>(BACKEND_AUTO), static_cast<double>(BACKEND_CUDA) });
  settings.push_back({ "Evaluation", static_cast<double>(this->Evaluation), static_cast<double>(EVALUATION_AUTO), static_cast<double>(EVALUATION_MULTIRESOLUTION) });
  settings.push_back({ "Accuracy", static_cast<double>(this->Accuracy), static_cast<double>(0.001), static_cast<double>(1.0) });
}

void vtkGLSScaleFilterBase::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MinScale: " << this->MinScale << "\n";
  os << indent << "MaxScale: " << this->MaxScale << "\n";
  os << indent << "NumberOfScales: " << this->NumberOfScales << "\n";
  os << indent << "ScaleSampling: " << this->ScaleSampling << "\n";
  os << indent << "ExplicitScales: " << this->ExplicitScales.size() << "\n";
  os << indent << "Backend: " << this->Backend << " (last used: " << this->LastBackendUsed << ")\n";
  os << indent << "Evaluation: " << this->Evaluation << " (last used: " << this->LastEvaluationUsed << ")\n";
  os << indent << "Accuracy: " << this->Accuracy << "\n";
}
