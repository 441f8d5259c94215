#include "vtkGLSNormalEstimation.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSRun.h"

#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"

#include "gls/NormalEstimation.h"
#include "gls/Planarity.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkGLSNormalEstimation);

vtkGLSNormalEstimation::vtkGLSNormalEstimation()
  : NeighborhoodType(K_NEAREST)
  , NumberOfNeighbors(16)
  , Radius(0.0)
  , Orientation(MINIMUM_SPANNING_TREE)
  , OrientationPoint{ 0.0, 0.0, 0.0 }
  , GraphNeighbors(10)
{
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::NORMALS);
}

vtkGLSNormalEstimation::~vtkGLSNormalEstimation() = default;

int vtkGLSNormalEstimation::Execute(vtkGLSRun& run)
{
  vtkPointSet* input = run.Input;
  const vtkIdType n = input->GetNumberOfPoints();
  const vtkGLSDistributedCloud& dist = run.Distributed;
  if (this->NeighborhoodType == RADIUS && !(this->Radius > 0.0 && std::isfinite(this->Radius)))
  {
    vtkErrorMacro("Radius must be a finite positive length in RADIUS mode (got " << this->Radius << ").");
    return FAILED;
  }
  if (dist.IsParallel())
  {
    const gls::PlaneZ plane = gls::commonZ(run.Cloud.Points.data(), run.Cloud.Owned);
    if (dist.AllInOnePlaneZ(plane.planar, plane.any, plane.z))
    {
      vtkErrorMacro("Distributed normal estimation of a planar input (every point in the plane z = "
        << run.Bounds[4] << ") is not supported: run it on one process.");
      return FAILED;
    }
  }

  gls::NormalEstimationSettings settings;
  settings.neighborhood = static_cast<gls::NeighborhoodType>(this->NeighborhoodType);
  settings.k = this->NumberOfNeighbors;
  settings.radius = this->Radius;
  settings.orientation = static_cast<gls::NormalOrientation>(this->Orientation);
  settings.viewpoint = { this->OrientationPoint[0], this->OrientationPoint[1], this->OrientationPoint[2] };
  settings.graphNeighbors = this->GraphNeighbors;
  settings.parallel.threads = this->NumberOfThreads;
  settings.parallel.progress = [this](double f) { return this->ReportProgress(f, 0.0, 0.9); };

  std::vector<double> reference;
  if (this->Orientation == AGREE_WITH_EXISTING)
  {
    std::string problem;
    bool absent = false;
    vtkDataArray* existing = n > 0 ? this->SelectNormals(0, input, problem, absent) : nullptr;
    if (!dist.AllTrue(existing || (dist.IsParallel() && n == 0)))
    {
      vtkErrorMacro("AGREE_WITH_EXISTING needs existing normals (a floating-point 3-component point array with one "
                    "tuple per point; select it with SetInputArrayToProcess, or set active normals): "
                    << (problem.empty() ? "another process has none" : problem) << ".");
      return FAILED;
    }
    reference.resize(3 * static_cast<std::size_t>(n));
    for (vtkIdType i = 0; i < n; ++i)
    {
      existing->GetTuple(i, &reference[3 * i]);
    }
    settings.reference = reference.data();
  }

  gls::NormalEstimationResult result;
  if (dist.IsParallel())
  {
    if (!this->EstimateDistributed(run, reference, settings, result))
    {
      return FAILED;
    }
  }
  else if (!gls::estimateNormals(run.Cloud.Points.data(), static_cast<std::size_t>(n), settings, result))
  {
    return ABORTED; // the output is the input, without partial normals
  }
  vtkNew<vtkDoubleArray> normals;
  normals->SetName(vtkGLSArrayNames::Normals);
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(n);
  std::copy(result.normals.begin(), result.normals.end(), normals->GetPointer(0));
  run.Output->GetPointData()->SetNormals(normals);
  this->UpdateProgress(1.0);
  return COMPLETED;
}

bool vtkGLSNormalEstimation::EstimateDistributed(vtkGLSRun& run, std::vector<double>& reference,
  gls::NormalEstimationSettings settings, gls::NormalEstimationResult& result)
{
  const vtkGLSDistributedCloud& dist = run.Distributed;
  std::vector<double>& xyz = run.Cloud.Points;
  const std::size_t n = run.Cloud.Owned;
  // Ghosts: every point within the reach of this piece's neighbourhoods.
  const double reach = settings.neighborhood == gls::NeighborhoodType::Radius
    ? settings.radius
    : gls::kNearestReach(xyz.data(), n, settings.k, settings.parallel);
  std::size_t ghostCount = 0;
  if (!dist.AllTrue(dist.AppendGhosts(xyz, n, {}, reach, ghostCount)))
  {
    vtkErrorMacro("The exchange of ghost points between the processes failed.");
    return false;
  }
  if (!reference.empty())
  {
    reference.resize(xyz.size(), std::numeric_limits<double>::quiet_NaN()); // ghosts: keep the solver's sign
    settings.reference = reference.data();
  }
  const bool mst = settings.orientation == gls::NormalOrientation::MinimumSpanningTree;
  if (mst)
  {
    settings.orientation = gls::NormalOrientation::None; // oriented below, over the whole cloud
  }
  settings.parallel.progress = nullptr; // no abort half-way through a collective run
  gls::NormalEstimationResult local;
  gls::estimateNormals(xyz.data(), n + ghostCount, settings, local);
  result.normals.assign(local.normals.begin(), local.normals.begin() + 3 * static_cast<std::ptrdiff_t>(n));
  result.neighborCounts.assign(
    local.neighborCounts.begin(), local.neighborCounts.begin() + static_cast<std::ptrdiff_t>(n));
  xyz.resize(3 * n);
  if (!mst)
  {
    return true;
  }

  // Minimum spanning tree over the whole cloud, on rank 0, in global-id order (the serial order).
  const std::vector<long long> ids = dist.GlobalIds(run.Input);
  std::vector<double> rows(7 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    rows[7 * i] = static_cast<double>(ids[i]);
    std::copy(&xyz[3 * i], &xyz[3 * i] + 3, &rows[7 * i + 1]);
    std::copy(&result.normals[3 * i], &result.normals[3 * i] + 3, &rows[7 * i + 4]);
  }
  std::vector<double> all;
  std::vector<long long> counts;
  if (!dist.GatherRows(rows, 7, 0, all, counts))
  {
    vtkErrorMacro("Gathering the points on rank 0 for the minimum-spanning-tree orientation failed.");
    return false;
  }
  std::vector<double> oriented;
  if (dist.GetRank() == 0)
  {
    const std::size_t total = all.size() / 7;
    std::vector<std::size_t> order(total);
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(),
      [&all](std::size_t a, std::size_t b) { return all[7 * a] < all[7 * b]; });
    std::vector<double> sortedXyz(3 * total), sortedNormals(3 * total);
    for (std::size_t j = 0; j < total; ++j)
    {
      std::copy(&all[7 * order[j] + 1], &all[7 * order[j] + 4], &sortedXyz[3 * j]);
      std::copy(&all[7 * order[j] + 4], &all[7 * order[j] + 7], &sortedNormals[3 * j]);
    }
    gls::orientByMinimumSpanningTree(sortedXyz.data(), total, settings.graphNeighbors, sortedNormals.data(),
      settings.parallel, result.components);
    oriented.resize(3 * total);
    for (std::size_t j = 0; j < total; ++j)
    {
      std::copy(&sortedNormals[3 * j], &sortedNormals[3 * j] + 3, &oriented[3 * order[j]]);
    }
  }
  std::vector<double> mine;
  if (!dist.ScatterRows(oriented, 3, 0, counts, mine))
  {
    vtkErrorMacro("Sending the oriented normals back from rank 0 failed.");
    return false;
  }
  result.normals = mine;
  return true;
}

void vtkGLSNormalEstimation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NeighborhoodType: " << (this->NeighborhoodType == K_NEAREST ? "KNearest" : "Radius") << "\n";
  os << indent << "NumberOfNeighbors: " << this->NumberOfNeighbors << "\n";
  os << indent << "Radius: " << this->Radius << "\n";
  os << indent << "Orientation: " << this->Orientation << "\n";
  os << indent << "OrientationPoint: " << this->OrientationPoint[0] << ", " << this->OrientationPoint[1] << ", "
     << this->OrientationPoint[2] << "\n";
  os << indent << "GraphNeighbors: " << this->GraphNeighbors << "\n";
}
