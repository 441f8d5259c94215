#include "vtkGLSScaleFilterBase.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSDistributedCloud.h"
#include "vtkGLSStoredScaleSpace.h"

#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include "gls/ScaleSampling.h"
#include "gls/ScaleSpaceEngine.h"
#include "gls/VariationSink.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

struct vtkGLSScaleFilterBase::Internals
{
  bool UseStored = false;
  vtkGLSStoredScaleSpace Stored;
  std::size_t PointCount = 0; ///< owned points (the input's)
  std::size_t ScaleCount = 0;
  std::vector<std::uint64_t> OwnedOrder; ///< distributed fits: the engine's order without the ghosts
  std::unique_ptr<gls::ScaleSpaceEngine> Engine;
};

vtkGLSScaleFilterBase::vtkGLSScaleFilterBase()
  : ScaleUnits(RELATIVE_TO_DIAGONAL)
  , MinScale(0.008)
  , MaxScale(0.08)
  , NumberOfScales(20)
  , ScaleSampling(QUADRATIC)
  , MinimumNeighbors(0)
  , WTau(1.0)
  , WEta(1.0)
  , WKappa(1.0)
  , ReuseInputScaleSpace(true)
  , Backend(BACKEND_AUTO)
  , MemoryBudget(0.0)
  , NumberOfThreads(0)
{
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::NORMALS);
  this->SetController(vtkMultiProcessController::GetGlobalController());
  this->DistributedRun = std::make_unique<vtkGLSDistributedCloud>(nullptr);
}

vtkGLSScaleFilterBase::~vtkGLSScaleFilterBase()
{
  this->SetController(nullptr);
}

vtkCxxSetObjectMacro(vtkGLSScaleFilterBase, Controller, vtkMultiProcessController);

bool vtkGLSScaleFilterBase::BeginRun(vtkPolyData* input)
{
  // Assigned in place: a filter may hold a reference to it across a call that begins the run again.
  *this->DistributedRun = vtkGLSDistributedCloud(this->Controller);
  this->GhostPointsUsed = -1;
  const vtkGLSDistributedCloud& dist = *this->DistributedRun;
  if (!dist.IsParallel())
  {
    return true;
  }
  if (!this->SupportsDistributedInput())
  {
    *this->DistributedRun = vtkGLSDistributedCloud(nullptr); // re-checked at every run
    vtkErrorMacro(<< this->GetClassName() << " is serial-only: it runs here on " << dist.GetSize()
                  << " processes, where each would see only its own piece of the cloud and give wrong values near "
                     "the piece boundaries. Run it in a serial pvpython/pvbatch (or on one process).");
    return false;
  }
  const vtkIdType n = input ? input->GetNumberOfPoints() : 0;
  std::vector<double> xyz(3 * static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    input->GetPoint(i, &xyz[3 * i]);
  }
  // Every rank takes part, an empty piece too: the diagonal is over the finite points of all the pieces.
  double b[6];
  const bool any = dist.FiniteBounds(xyz.data(), static_cast<std::size_t>(n), b);
  const double dx = b[1] - b[0], dy = b[3] - b[2], dz = b[5] - b[4];
  this->DistributedDiagonal = any ? std::sqrt(dx * dx + dy * dy + dz * dz) : 0.0;
  if (!(dist.Sum(static_cast<double>(n)) > 0.0))
  {
    vtkErrorMacro("The input has no points (on any of the " << dist.GetSize() << " processes).");
    return false;
  }
  return true;
}

double vtkGLSScaleFilterBase::InputDiagonal(vtkPolyData* input) const
{
  return this->DistributedRun && this->DistributedRun->IsParallel() ? this->DistributedDiagonal
                                                                     : FiniteDiagonal(input);
}

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

int vtkGLSScaleFilterBase::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

double vtkGLSScaleFilterBase::ToAbsoluteLength(vtkPolyData* input, double value) const
{
  if (this->ScaleUnits == ABSOLUTE)
  {
    return value;
  }
  return value * this->InputDiagonal(input);
}

double vtkGLSScaleFilterBase::FiniteDiagonal(vtkPolyData* input)
{
  // Over the points with finite coordinates only: one NaN or Inf point must not change everyone's scales.
  double lo[3] = { 0, 0, 0 }, hi[3] = { 0, 0, 0 };
  bool any = false;
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])))
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = any ? std::min(lo[a], p[a]) : p[a];
      hi[a] = any ? std::max(hi[a], p[a]) : p[a];
    }
    any = true;
  }
  const double dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

std::vector<double> vtkGLSScaleFilterBase::ComputeAbsoluteScales(vtkPolyData* input)
{
  std::vector<double> scales;
  if (this->ScaleUnits == RELATIVE_TO_DIAGONAL && !(this->InputDiagonal(input) > 0.0))
  {
    vtkErrorMacro("Invalid scales: they are relative to the bounding-box diagonal, and it is zero (all points with "
                  "finite coordinates coincide, or there are none): set ScaleUnits to ABSOLUTE.");
    return {};
  }
  if (!this->ExplicitScales.empty())
  {
    for (double s : this->ExplicitScales)
    {
      scales.push_back(this->ToAbsoluteLength(input, s));
    }
    const std::string why = gls::checkScaleList(scales);
    if (!why.empty())
    {
      vtkErrorMacro("Invalid scales: " << why << ".");
      return {};
    }
    return scales;
  }
  const double tmin = this->ToAbsoluteLength(input, this->MinScale);
  const double tmax = this->ToAbsoluteLength(input, this->MaxScale);
  std::string why = gls::checkScaleRange(this->MinScale, this->MaxScale, this->NumberOfScales);
  if (why.empty())
  {
    why = gls::checkScaleRange(tmin, tmax, this->NumberOfScales);
  }
  if (!why.empty())
  {
    vtkErrorMacro("Invalid scales: " << why
                                     << (this->ScaleUnits == RELATIVE_TO_DIAGONAL
                                            ? " (scales are relative to the bounding-box diagonal)."
                                            : "."));
    return {};
  }
  return gls::sampleScales(
    tmin, tmax, this->NumberOfScales, static_cast<gls::ScaleSampling>(this->ScaleSampling));
}

bool vtkGLSScaleFilterBase::GatherPointsAndNormals(
  vtkPolyData* input, std::vector<double>& points, std::vector<double>& normals)
{
  const vtkIdType n = input->GetNumberOfPoints();
  const bool parallel = this->DistributedRun && this->DistributedRun->IsParallel();
  if (n < 1)
  {
    if (parallel)
    {
      points.clear(); // an empty piece of a distributed input (BeginRun checked that some rank has points)
      normals.clear();
      return true;
    }
    vtkErrorMacro("The input has no points.");
    return false;
  }
  vtkDataArray* nrm = this->FindSelectedNormals(input);
  if (!nrm)
  {
    vtkErrorMacro("The input has no normals: select a 3-component point array, set active normals, or run "
                  "vtkGLSNormalEstimation (GLS Normal Estimation) first.");
    return false;
  }
  if (nrm->GetNumberOfComponents() != 3 || nrm->GetNumberOfTuples() != n)
  {
    vtkErrorMacro("The normals array '" << (nrm->GetName() ? nrm->GetName() : "(unnamed)") << "' has "
                                        << nrm->GetNumberOfComponents() << " components and "
                                        << nrm->GetNumberOfTuples() << " tuples; expected 3 components and " << n
                                        << " tuples (one per point).");
    return false;
  }
  points.resize(3 * static_cast<std::size_t>(n));
  normals.resize(3 * static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    input->GetPoint(i, &points[3 * i]);
    nrm->GetTuple(i, &normals[3 * i]);
  }
  return true;
}

vtkDataArray* vtkGLSScaleFilterBase::FindSelectedNormals(vtkPolyData* input)
{
  return vtkGLSScaleFilterBase::FindSelectedNormals(this, 0, input);
}

vtkDataArray* vtkGLSScaleFilterBase::FindSelectedNormals(vtkAlgorithm* self, int index, vtkPolyData* input)
{
  // A selection by name must be honoured; no selection means the active normals.
  const char* name = SelectedArrayName(self, index);
  return name ? input->GetPointData()->GetArray(name) : input->GetPointData()->GetNormals();
}

const char* vtkGLSScaleFilterBase::SelectedArrayName(vtkAlgorithm* self, int index)
{
  vtkInformation* info = self->GetInputArrayInformation(index);
  const char* name = info && info->Has(vtkDataObject::FIELD_NAME()) ? info->Get(vtkDataObject::FIELD_NAME()) : nullptr;
  return name && name[0] != '\0' ? name : nullptr;
}

double vtkGLSScaleFilterBase::ResolveMinimumNeighbors(
  const std::vector<double>& points, const std::vector<double>& normals) const
{
  if (this->MinimumNeighbors > 0)
  {
    return this->MinimumNeighbors;
  }
  // A 2D curve: every point in the plane z = const (the first point's z) with normals in that plane. In a
  // distributed run every piece must agree, on the same plane.
  const std::size_t n = points.size() / 3;
  bool flat = true;
  for (std::size_t i = 0; i < n && flat; ++i)
  {
    flat = !(points[3 * i + 2] != points[2] || normals[3 * i + 2] != 0.0);
  }
  const vtkGLSDistributedCloud& dist = *this->DistributedRun;
  if (dist.IsParallel())
  {
    const double inf = std::numeric_limits<double>::infinity();
    const bool allFlat = dist.AllTrue(flat);
    const double zmin = dist.Min(n > 0 ? points[2] : inf), zmax = dist.Max(n > 0 ? points[2] : -inf);
    flat = allFlat && zmin == zmax;
  }
  return flat ? 3.0 : 6.0;
}

bool vtkGLSScaleFilterBase::ReportProgress(double fraction, double begin, double end)
{
  this->UpdateProgress(begin + fraction * (end - begin));
  return this->GetAbortExecute() != 0;
}

bool vtkGLSScaleFilterBase::PrepareScaleSamples(vtkPolyData* input, bool needDescriptors, bool needDerivatives,
  std::vector<double>& scales, const OutputCost& cost)
{
  this->Source = std::make_unique<Internals>();
  Internals& src = *this->Source;
  src.PointCount = static_cast<std::size_t>(input->GetNumberOfPoints());
  if (!this->DistributedRun->IsParallel() && !this->BeginRun(input))
  {
    return false; // (a filter that called PrepareOutput has begun its run already)
  }
  const vtkGLSDistributedCloud& dist = *this->DistributedRun;
  if (src.PointCount == 0 && !dist.IsParallel())
  {
    vtkErrorMacro("The input has no points.");
    return false;
  }
  scales.clear();
  if (this->ReuseInputScaleSpace && this->AcceptsStoredScaleSpace())
  {
    scales = ReadStoredScales(input->GetFieldData());
  }
  const double n = static_cast<double>(src.PointCount);
  // Stored arrays need no neighbours; every rank must take the same path (an empty piece goes along).
  const bool bound = !scales.empty() && src.Stored.Bind(input, scales.size(), needDescriptors, needDerivatives);
  if (dist.AllTrue(bound || (dist.IsParallel() && src.PointCount == 0)) &&
    (!dist.IsParallel() || dist.Max(bound ? 1.0 : 0.0) > 0.5))
  {
    src.UseStored = true;
    src.ScaleCount = scales.size();
    return this->CheckMemoryBudget(n * static_cast<double>(scales.size()) * cost.BytesPerPointScale, cost.What,
      cost.Advice);
  }

  src.UseStored = false;
  scales = this->ComputeAbsoluteScales(input);
  std::vector<double> points, normals;
  bool ok = !scales.empty() &&
    this->CheckMemoryBudget(n * static_cast<double>(scales.size()) * cost.BytesPerPointScale +
        this->EngineBytes(input->GetNumberOfPoints(), scales.size()),
      cost.What, cost.Advice) &&
    this->GatherPointsAndNormals(input, points, normals);
  if (!dist.AllTrue(ok))
  {
    if (ok)
    {
      vtkErrorMacro("Stopped: another process of this distributed run failed (see its error).");
    }
    return false;
  }
  gls::ScaleSpaceSettings settings;
  settings.scales = scales;
  settings.minNeighbors = this->ResolveMinimumNeighbors(points, normals);
  settings.parallel.threads = this->NumberOfThreads;
  src.ScaleCount = scales.size();
  if (!dist.IsParallel())
  {
    src.Engine = std::make_unique<gls::ScaleSpaceEngine>(points.data(), normals.data(), src.PointCount, settings);
    return true;
  }
  // Distributed: the other pieces' points within the largest scale of this piece (with their normals) join the
  // engine after the owned points; only the owned ones are evaluated.
  std::vector<double> rows(6 * src.PointCount);
  for (std::size_t i = 0; i < src.PointCount; ++i)
  {
    std::copy(&points[3 * i], &points[3 * i] + 3, &rows[6 * i]);
    std::copy(&normals[3 * i], &normals[3 * i] + 3, &rows[6 * i + 3]);
  }
  std::vector<double> ghosts;
  std::size_t ghostCount = 0;
  ok = dist.ExchangeGhosts(rows.data(), src.PointCount, 6, scales.back(), ghosts, ghostCount);
  if (!dist.AllTrue(ok))
  {
    vtkErrorMacro("The exchange of ghost points between the processes failed.");
    return false;
  }
  this->GhostPointsUsed = static_cast<long long>(ghostCount);
  if (src.PointCount == 0)
  {
    return true; // an empty piece: nothing to fit
  }
  for (std::size_t g = 0; g < ghostCount; ++g)
  {
    points.insert(points.end(), &ghosts[6 * g], &ghosts[6 * g] + 3);
    normals.insert(normals.end(), &ghosts[6 * g + 3], &ghosts[6 * g] + 6);
  }
  src.Engine = std::make_unique<gls::ScaleSpaceEngine>(
    points.data(), normals.data(), src.PointCount + ghostCount, settings);
  for (std::uint64_t id : src.Engine->evaluationOrder())
  {
    if (id < src.PointCount)
    {
      src.OwnedOrder.push_back(id);
    }
  }
  return true;
}

bool vtkGLSScaleFilterBase::ReduceVariationPerPoint(vtkPolyData* input, const VariationReducer& reduce,
  std::vector<double>& scales, double* out, double progressEnd, bool& aborted)
{
  aborted = false;
  const vtkIdType n = input->GetNumberOfPoints();
  scales = this->ReuseInputScaleSpace && this->AcceptsStoredScaleSpace() ? ReadStoredScales(input->GetFieldData())
                                                                         : std::vector<double>();
  vtkDataArray* storedNu = input->GetPointData()->GetArray(vtkGLSArrayNames::Variation);
  if (!this->DistributedRun->IsParallel() && !this->BeginRun(input))
  {
    return false;
  }
  const vtkGLSDistributedCloud& dist = *this->DistributedRun;
  const bool haveNu = !scales.empty() && storedNu &&
    storedNu->GetNumberOfComponents() == static_cast<int>(scales.size()) && storedNu->GetNumberOfTuples() == n;
  // Every rank must take the same path (an empty piece goes along).
  if (dist.AllTrue(haveNu || (dist.IsParallel() && n == 0)) &&
    (!dist.IsParallel() || dist.Max(haveNu ? 1.0 : 0.0) > 0.5))
  {
    std::vector<double> nu(scales.size());
    for (vtkIdType i = 0; i < n; ++i)
    {
      storedNu->GetTuple(i, nu.data());
      out[i] = reduce(nu.data(), scales);
      if (i % 65536 == 0 && this->ReportProgress(static_cast<double>(i) / n, 0.0, progressEnd))
      {
        aborted = true;
        return true;
      }
    }
    return true;
  }
  if (!this->PrepareScaleSamples(input, false, true, scales))
  {
    return false;
  }
  gls::VariationReductionSink sink(scales, gls::resolveThreadCount(this->NumberOfThreads),
    { this->WTau, this->WEta, this->WKappa }, [&](const double* nu) { return reduce(nu, scales); }, out);
  aborted = !this->RunScaleSamples(sink, nullptr, 0.0, progressEnd);
  return true;
}

bool vtkGLSScaleFilterBase::RunScaleSamples(
  gls::ScaleSampleSink& sink, const std::vector<std::uint64_t>* ids, double progressBegin, double progressEnd)
{
  Internals& src = *this->Source;
  gls::ParallelOptions parallel;
  parallel.threads = this->NumberOfThreads;
  parallel.progress = [this, progressBegin, progressEnd](double f) {
    return this->ReportProgress(f, progressBegin, progressEnd);
  };
  if (!src.UseStored)
  {
    if (!src.Engine)
    {
      return true; // an empty piece of a distributed input
    }
    const bool distributed = this->DistributedRun->IsParallel();
    return this->RunEngine(*src.Engine, sink, ids || !distributed ? ids : &src.OwnedOrder, parallel);
  }
  const std::size_t n = ids ? ids->size() : src.PointCount;
  const int threads = gls::resolveThreadCount(this->NumberOfThreads);
  std::vector<std::vector<gls::ScaleSample>> buffers(static_cast<std::size_t>(threads));
  return gls::parallelFor(n, parallel, [&](std::size_t begin, std::size_t end, int thread) {
    std::vector<gls::ScaleSample>& b = buffers[thread];
    b.resize(src.ScaleCount);
    for (std::size_t i = begin; i < end; ++i)
    {
      const std::uint64_t id = ids ? (*ids)[i] : i;
      src.Stored.Read(id, b.data());
      sink.consume(id, b.data(), thread);
    }
  });
}

bool vtkGLSScaleFilterBase::RunEngine(const gls::ScaleSpaceEngine& engine, gls::ScaleSampleSink& sink,
  const std::vector<std::uint64_t>* ids, const gls::ParallelOptions& parallel)
{
  gls::RunReport report;
  const bool completed = engine.run(
    sink, ids, gls::EvaluationMethod::OnePass, &parallel, static_cast<gls::Backend>(this->Backend), &report);
  this->LastBackendUsed = gls::backendName(report.used);
  if (this->Backend == BACKEND_CUDA && report.used != gls::Backend::CUDA && !this->WarnedAboutBackend)
  {
    this->WarnedAboutBackend = true;
    vtkWarningMacro("Backend CUDA requested but not available (" << report.fallbackReason
                                                                  << "); computing on the CPU instead.");
  }
  return completed;
}

bool vtkGLSScaleFilterBase::CheckMemoryBudget(double needed, const char* what, const char* advice)
{
  double budget = this->MemoryBudget * 1024.0 * 1024.0;
  if (!(budget > 0.0))
  {
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
    budget = pages > 0 && pageSize > 0 ? 0.5 * static_cast<double>(pages) * static_cast<double>(pageSize) : 4e9;
  }
  if (needed <= budget)
  {
    return true;
  }
  vtkErrorMacro("Not enough memory budget: " << what << " needs about " << needed / (1024.0 * 1024.0)
                                             << " MiB, above the budget of " << budget / (1024.0 * 1024.0)
                                             << " MiB (MemoryBudget; 0 = half of the physical memory). " << advice);
  return false;
}

double vtkGLSScaleFilterBase::EngineBytes(vtkIdType n, std::size_t S) const
{
  const double threads = gls::resolveThreadCount(this->NumberOfThreads);
  const double perPoint = 6 * 8 + 2 * 3 * 8 + 3 * 8 + 8; // input copies, grid copies, positions, order
  const double perThread = static_cast<double>(S) * (sizeof(gls::Moments) + sizeof(gls::ScaleSample) + 8);
  return static_cast<double>(n) * perPoint + threads * perThread;
}

void vtkGLSScaleFilterBase::StoreBackend(vtkFieldData* fd) const
{
  if (this->DistributedRun && this->DistributedRun->IsParallel() && this->GhostPointsUsed >= 0)
  {
    vtkNew<vtkIdTypeArray> ghosts;
    ghosts->SetName(vtkGLSArrayNames::GhostPoints);
    ghosts->InsertNextValue(static_cast<vtkIdType>(this->GhostPointsUsed));
    fd->AddArray(ghosts);
  }
  if (this->LastBackendUsed.empty())
  {
    return;
  }
  vtkNew<vtkStringArray> a;
  a->SetName(vtkGLSArrayNames::Backend);
  a->InsertNextValue(this->LastBackendUsed);
  fd->AddArray(a);
}

bool vtkGLSScaleFilterBase::PrepareOutput(vtkPolyData* input, vtkPolyData* output)
{
  this->LastBackendUsed.clear();
  output->ShallowCopy(input);
  vtkNew<vtkFieldData> fd;
  fd->ShallowCopy(input->GetFieldData());
  output->SetFieldData(fd);
  if (!this->BeginRun(input))
  {
    return false;
  }
  if (input->GetNumberOfPoints() < 1 && !this->DistributedRun->IsParallel())
  {
    vtkErrorMacro("The input has no points.");
    return false;
  }
  return true;
}

void vtkGLSScaleFilterBase::StoreScales(vtkFieldData* fd, const std::vector<double>& scales)
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

void vtkGLSScaleFilterBase::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ScaleUnits: " << (this->ScaleUnits == ABSOLUTE ? "Absolute" : "RelativeToDiagonal") << "\n";
  os << indent << "MinScale: " << this->MinScale << "\n";
  os << indent << "MaxScale: " << this->MaxScale << "\n";
  os << indent << "NumberOfScales: " << this->NumberOfScales << "\n";
  os << indent << "ScaleSampling: " << this->ScaleSampling << "\n";
  os << indent << "ExplicitScales: " << this->ExplicitScales.size() << "\n";
  os << indent << "MinimumNeighbors: " << this->MinimumNeighbors << "\n";
  os << indent << "WTau, WEta, WKappa: " << this->WTau << ", " << this->WEta << ", " << this->WKappa << "\n";
  os << indent << "ReuseInputScaleSpace: " << this->ReuseInputScaleSpace << "\n";
  os << indent << "Backend: " << this->Backend << " (last used: " << this->LastBackendUsed << ")\n";
  os << indent << "MemoryBudget (MiB): " << this->MemoryBudget << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
}
