#include "vtkGLSProjection.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSRun.h"

#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPointSet.h"

#include "gls/MlsProjection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

vtkStandardNewMacro(vtkGLSProjection);

vtkGLSProjection::vtkGLSProjection()
  : ScaleMode(AUTOMATIC)
  , Scale(0.01)
  , MaxIterations(50)
  , Tolerance(1e-6)
{
  this->SetInputArrayToProcess(
    1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkGLSArrayNames::Bandwidth);
}

vtkGLSProjection::~vtkGLSProjection() = default;

int vtkGLSProjection::Execute(vtkGLSRun& run)
{
  this->LastScaleMode = AUTOMATIC;
  if (!this->CheckFitParameters())
  {
    return FAILED;
  }
  std::vector<double> scales;
  int mode = AUTOMATIC;
  vtkPointSet* input = run.Input;
  const vtkIdType n = input->GetNumberOfPoints();
  const std::size_t count = static_cast<std::size_t>(n);
  // Outputs plus the core's copies of points and normals and its grid.
  const bool ok = this->GatherNormals(run) && this->ResolveSupports(run, scales, mode) &&
    this->CheckMemoryBudget(static_cast<double>(count) * (3 * 8 + 3 * 8 + 8 + 4 + 1 + 7 * 8), "the projection",
      "Use fewer points.");
  if (!this->AgreeToContinue(run, ok))
  {
    return FAILED;
  }
  this->WarnAboutNormalLengths(run, run.Cloud.Normals, run.NormalsName.c_str());
  this->NoteCoincidentPoints(
    run, gls::findCoincidentPoints(run.Cloud.Points.data(), run.Cloud.Owned, this->NumberOfThreads).merged());

  vtkNew<vtkPoints> moved;
  moved->SetDataTypeToDouble();
  moved->SetNumberOfPoints(n);
  vtkNew<vtkDoubleArray> eta;
  eta->SetName(vtkGLSArrayNames::Normals);
  eta->SetNumberOfComponents(3);
  eta->SetNumberOfTuples(n);
  vtkNew<vtkDoubleArray> displacement;
  displacement->SetName(vtkGLSArrayNames::Displacement);
  displacement->SetNumberOfTuples(n);
  vtkNew<vtkIntArray> iterations;
  iterations->SetName(vtkGLSArrayNames::ProjectionIterations);
  iterations->SetNumberOfTuples(n);
  std::vector<unsigned char> converged(count);

  this->ResolveMinimumNeighbors(run);
  gls::ProjectionSettings settings;
  settings.minNeighbors = run.MinimumNeighbors;
  settings.maxIterations = this->MaxIterations;
  settings.tolerance = this->Tolerance;
  settings.parallel.threads = this->NumberOfThreads;
  settings.parallel.chunk = 64;
  settings.parallel.progress = [this](double f) { return this->ReportProgress(f, 0.0, 1.0); };
  const gls::ProjectionOutputs out{ static_cast<double*>(moved->GetData()->GetVoidPointer(0)), eta->GetPointer(0),
    displacement->GetPointer(0), iterations->GetPointer(0), converged.data() };
  if (run.Distributed.IsParallel())
  {
    if (!this->ProjectDistributed(run, scales, settings, out))
    {
      return FAILED;
    }
  }
  else if (!this->ProjectMerged(run.Cloud, scales, settings, out))
  {
    return ABORTED; // the input passes through, no partial arrays
  }
  // The projected positions in the input's coordinates: each input position moved as its point was in the run's
  // (a point left in place, one left out of the run among them, keeps its coordinates bit for bit).
  double* xyz = out.points;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    for (int a = 0; a < 3; ++a)
    {
      const double moved = xyz[3 * i + a] - run.Cloud.Points[3 * i + a];
      xyz[3 * i + a] = moved == 0.0 || !std::isfinite(moved) ? p[a] : p[a] + moved;
    }
  }
  this->LastScaleMode = mode;
  vtkPointSet* output = run.Output;
  output->SetPoints(moved);
  vtkPointData* pd = output->GetPointData();
  pd->RemoveArray(vtkGLSArrayNames::Normals);
  pd->AddArray(eta);
  pd->SetNormals(eta);
  pd->AddArray(displacement);
  pd->AddArray(iterations);
  pd->SetActiveScalars(vtkGLSArrayNames::Displacement);
  run.BackendUsed = "CPU";
  WriteRunFieldData(run, output->GetFieldData());
  return COMPLETED;
}

bool vtkGLSProjection::ProjectMerged(vtkGLSCloud cloud, const std::vector<double>& scales,
  const gls::ProjectionSettings& settings, const gls::ProjectionOutputs& out)
{
  const std::size_t n = cloud.Size();
  cloud.Owned = n; // every point is projected (the ghosts of a distributed pass have NaN scales: left in place)
  if (cloud.MergeCoincident() == 0)
  {
    return gls::projectPointCloud(cloud.Points.data(), cloud.Normals.data(), n, scales.data(), settings, out);
  }
  // Each distinct position once, at its first copy's scale; the results go back to every copy.
  const std::size_t m = cloud.Size();
  const std::vector<double> t = gls::distinctValues(cloud.Copies, scales.data(), 1);
  std::vector<double> moved(3 * m), eta(3 * m), displacement(m), iterations(m), converged(m);
  std::vector<int> iterationCounts(m);
  std::vector<unsigned char> convergedFlags(m);
  const gls::ProjectionOutputs distinct{ moved.data(), eta.data(), displacement.data(), iterationCounts.data(),
    convergedFlags.data() };
  if (!gls::projectPointCloud(cloud.Points.data(), cloud.Normals.data(), m, t.data(), settings, distinct))
  {
    return false;
  }
  std::copy(iterationCounts.begin(), iterationCounts.end(), iterations.begin());
  std::copy(convergedFlags.begin(), convergedFlags.end(), converged.begin());
  std::vector<double> iterationsOut(n), convergedOut(n);
  cloud.ScatterToInput(moved.data(), 3, out.points);
  cloud.ScatterToInput(eta.data(), 3, out.normals);
  cloud.ScatterToInput(displacement.data(), 1, out.displacement);
  cloud.ScatterToInput(iterations.data(), 1, iterationsOut.data());
  cloud.ScatterToInput(converged.data(), 1, convergedOut.data());
  for (std::size_t i = 0; i < n; ++i)
  {
    out.iterations[i] = static_cast<int>(iterationsOut[i]);
    out.converged[i] = static_cast<unsigned char>(convergedOut[i]);
  }
  return true;
}

bool vtkGLSProjection::ResolveSupports(const vtkGLSRun& run, std::vector<double>& scales, int& mode)
{
  vtkPointSet* input = run.Input;
  const vtkIdType n = input->GetNumberOfPoints();
  const std::size_t count = static_cast<std::size_t>(n);
  const char* selected = this->SelectedArrayName(1);
  vtkDataArray* bandwidth = input->GetPointData()->GetArray(selected ? selected : vtkGLSArrayNames::Bandwidth);
  mode = this->ScaleMode;
  if (mode == AUTOMATIC)
  {
    if (!bandwidth)
    {
      // A selection made before the input's arrays were known (a script that did not update the input first).
      bandwidth = input->GetPointData()->GetArray(vtkGLSArrayNames::Bandwidth);
    }
    mode = bandwidth ? BANDWIDTH_ARRAY : FIXED_SCALE;
  }
  scales.assign(count, 0.0);
  if (mode == BANDWIDTH_ARRAY)
  {
    if (!bandwidth)
    {
      vtkErrorMacro("No bandwidth array: run GLS Adaptive Bandwidth first (it writes GLSBandwidth), select the "
                    "array with SetInputArrayToProcess(1, ...), or use ScaleMode FIXED_SCALE.");
      return false;
    }
    if (bandwidth->GetNumberOfComponents() != 1 || bandwidth->GetNumberOfTuples() != n)
    {
      vtkErrorMacro("The bandwidth array " << (bandwidth->GetName() ? bandwidth->GetName() : "(unnamed)")
                                           << " must have 1 component and " << n << " tuples; it has "
                                           << bandwidth->GetNumberOfComponents() << " and "
                                           << bandwidth->GetNumberOfTuples() << ".");
      return false;
    }
    for (vtkIdType i = 0; i < n; ++i)
    {
      scales[static_cast<std::size_t>(i)] = bandwidth->GetComponent(i, 0);
    }
  }
  else
  {
    const double t = this->ToAbsoluteLength(run, this->Scale);
    if (!(t > 0.0) || !std::isfinite(t))
    {
      vtkErrorMacro("Scale must be positive (it is " << this->Scale
                                                     << (this->ScaleUnits == RELATIVE_TO_DIAGONAL
                                                            ? " of the bounding-box diagonal)."
                                                            : ")."));
      return false;
    }
    std::fill(scales.begin(), scales.end(), t);
  }
  return true;
}

bool vtkGLSProjection::ProjectDistributed(vtkGLSRun& run, const std::vector<double>& scales,
  gls::ProjectionSettings settings, const gls::ProjectionOutputs& out)
{
  const vtkGLSDistributedCloud& dist = run.Distributed;
  const std::size_t n = run.Cloud.Owned;
  double tmax = 0.0;
  for (double t : scales)
  {
    tmax = std::isfinite(t) ? std::max(tmax, t) : tmax;
  }
  tmax = dist.Max(tmax);
  settings.parallel.progress = nullptr; // no abort half-way through a collective run
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Ghosts within twice the largest support; a point that ends further than its support from that band (its last
  // fit then lacked neighbours) makes every rank redo the projection with the band doubled.
  for (double reach = 2.0 * tmax;; reach *= 2.0)
  {
    vtkGLSCloud cloud = run.Cloud;
    std::size_t ghostCount = 0;
    if (!dist.AllTrue(dist.AppendGhosts(cloud.Points, n, { { &cloud.Normals, 3 } }, reach, ghostCount)))
    {
      vtkErrorMacro("The exchange of ghost points between the processes failed.");
      return false;
    }
    run.GhostPoints = static_cast<long long>(ghostCount);
    const std::size_t total = n + ghostCount;
    std::vector<double> t(scales);
    t.resize(total, nan); // ghosts are neighbours only: a NaN scale leaves them in place
    std::vector<double> movedAll(3 * total), etaAll(3 * total), moveAll(total);
    std::vector<int> iterationsAll(total);
    std::vector<unsigned char> convergedAll(total);
    const gls::ProjectionOutputs all{ movedAll.data(), etaAll.data(), moveAll.data(), iterationsAll.data(),
      convergedAll.data() };
    this->ProjectMerged(cloud, t, settings, all);
    bool inside = true;
    for (std::size_t i = 0; i < n && inside; ++i)
    {
      inside = !(moveAll[i] + scales[i] > reach); // NaN displacement: not projected, nothing to check
    }
    if (dist.AllTrue(inside) || !(reach > 0.0) || reach > 2.0 * run.Diagonal)
    {
      std::copy(movedAll.begin(), movedAll.begin() + 3 * static_cast<std::ptrdiff_t>(n), out.points);
      std::copy(etaAll.begin(), etaAll.begin() + 3 * static_cast<std::ptrdiff_t>(n), out.normals);
      std::copy(moveAll.begin(), moveAll.begin() + static_cast<std::ptrdiff_t>(n), out.displacement);
      std::copy(iterationsAll.begin(), iterationsAll.begin() + static_cast<std::ptrdiff_t>(n), out.iterations);
      std::copy(convergedAll.begin(), convergedAll.begin() + static_cast<std::ptrdiff_t>(n), out.converged);
      return true;
    }
  }
}

void vtkGLSProjection::DescribeSettings(std::vector<SettingRange>& settings)
{
  this->Superclass::DescribeSettings(settings);
  settings.push_back({ "ScaleMode", static_cast<double>(this->ScaleMode), static_cast<double>(AUTOMATIC), static_cast<double>(BANDWIDTH_ARRAY) });
  settings.push_back({ "Scale", static_cast<double>(this->Scale), static_cast<double>(0.0), static_cast<double>(VTK_DOUBLE_MAX) });
  settings.push_back({ "MaxIterations", static_cast<double>(this->MaxIterations), static_cast<double>(1), static_cast<double>(100000) });
  settings.push_back({ "Tolerance", static_cast<double>(this->Tolerance), static_cast<double>(0.0), static_cast<double>(1.0) });
}

void vtkGLSProjection::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ScaleMode: " << this->ScaleMode << "\n";
  os << indent << "Scale: " << this->Scale << "\n";
  os << indent << "MaxIterations: " << this->MaxIterations << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
}
