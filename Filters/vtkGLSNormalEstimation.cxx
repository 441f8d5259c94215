#include "vtkGLSNormalEstimation.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSOutputPrecision.h"
#include "vtkGLSRun.h"

#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include "gls/CoincidentPoints.h"
#include "gls/NormalEstimation.h"
#include "gls/OrientationChoice.h"
#include "gls/Planarity.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkGLSNormalEstimation);

vtkGLSNormalEstimation::vtkGLSNormalEstimation()
  : NeighborhoodType(K_NEAREST)
  , NumberOfNeighbors(16)
  , Radius(0.0)
  , Orientation(AUTOMATIC)
  , OrientationPoint{ 0.0, 0.0, 0.0 }
  , UpDirection{ 0.0, 0.0, 1.0 }
  , GraphNeighbors(10)
  , MinimumSpread(0.05)
  , MaximumGrowth(8.0)
  , Refinement(NO_REFINEMENT)
  , RefinementScale(1.5)
  , OutputPrecision(vtkAlgorithm::DOUBLE_PRECISION)
{
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::NORMALS);
}

vtkGLSNormalEstimation::~vtkGLSNormalEstimation() = default;

namespace
{
/// Points the automatic radius is measured on (a regular stride through the cloud).
constexpr std::size_t kAutomaticRadiusSamples = 10000;
}

int vtkGLSNormalEstimation::Execute(vtkGLSRun& run)
{
  gls::NormalEstimationSettings settings;
  OrientationPlan plan;
  std::vector<double> reference;
  if (!this->CheckRun(run) || !this->PlanOrientation(run, plan))
  {
    return FAILED;
  }
  this->ResolveSettings(run, plan, settings);
  if (!this->GatherReference(run, plan, reference, settings) ||
    !this->AgreeToContinue(run, this->CheckMemoryBudget(this->NeededBytes(run, settings, reference),
                                  "the normal estimation",
                                  "Use fewer NumberOfNeighbors or GraphNeighbors, or raise MemoryBudget.")))
  {
    return FAILED;
  }
  gls::NormalEstimationResult result;
  if (run.Distributed.IsParallel())
  {
    if (!this->EstimateDistributed(run, reference, settings, result) ||
      (this->Refinement == GLS_REFINEMENT && !this->RefineDistributed(run, settings.parallel, result)))
    {
      return FAILED;
    }
  }
  else
  {
    const int status = this->EstimateSerial(run, reference, settings, result);
    if (status != COMPLETED)
    {
      return status;
    }
  }
  this->WriteNormals(run, settings, plan, result);
  this->UpdateProgress(1.0);
  return COMPLETED;
}

bool vtkGLSNormalEstimation::CheckRun(const vtkGLSRun& run)
{
  const vtkGLSDistributedCloud& dist = run.Distributed;
  const bool byRadius = this->NeighborhoodType == RADIUS;
  if (byRadius && !(this->Radius >= 0.0 && std::isfinite(this->Radius)))
  {
    vtkErrorMacro("Radius must be a finite length >= 0 in RADIUS mode (0: automatic; got " << this->Radius << ").");
    return false;
  }
  if (byRadius && this->Radius == 0.0 && dist.IsParallel())
  {
    vtkErrorMacro("The automatic Radius (0) is measured on the whole cloud and is not supported on several "
                  "processes: set Radius to a length (a serial run records the automatic one in GLSNormalRadius).");
    return false;
  }
  if (dist.IsParallel())
  {
    const gls::PlaneZ plane = gls::commonZ(run.Cloud.Points.data(), run.Cloud.Owned);
    if (dist.AllInOnePlaneZ(plane.planar, plane.any, plane.z))
    {
      vtkErrorMacro("Distributed normal estimation of a planar input (every point in the plane z = "
        << run.Bounds[4] << ") is not supported: run it on one process.");
      return false;
    }
  }
  return true;
}

namespace
{

/// "(x, y, z)" of a point or direction.
std::string Triple(const double* v)
{
  std::ostringstream s;
  s.precision(10);
  s << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
  return s.str();
}

/// The values of a point array of n tuples (one component) in type T, or empty when the input has no such array.
template <typename T, typename Array>
std::vector<T> ValuesNamed(vtkPointSet* input, const char* name)
{
  vtkDataArray* a = input->GetPointData()->GetArray(name);
  const vtkIdType n = input->GetNumberOfPoints();
  std::vector<T> values;
  if (!a || a->GetNumberOfComponents() != 1 || a->GetNumberOfTuples() != n)
  {
    return values;
  }
  values.resize(static_cast<std::size_t>(n));
  if (auto* typed = Array::FastDownCast(a))
  {
    std::copy(typed->GetPointer(0), typed->GetPointer(0) + n, values.begin());
    return values;
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    // Another type's value as T; out of T's range (a NaN included): T's largest, which no rule takes for evidence.
    const double v = a->GetComponent(i, 0);
    const bool inRange = v >= static_cast<double>(std::numeric_limits<T>::lowest()) &&
      v <= static_cast<double>(std::numeric_limits<T>::max());
    values[static_cast<std::size_t>(i)] = inRange ? static_cast<T>(v) : std::numeric_limits<T>::max();
  }
  return values;
}

} // namespace

bool vtkGLSNormalEstimation::PlanOrientation(const vtkGLSRun& run, OrientationPlan& plan)
{
  plan = OrientationPlan();
  plan.Mode = this->Orientation;
  std::copy(this->OrientationPoint, this->OrientationPoint + 3, plan.Point);
  std::copy(this->UpDirection, this->UpDirection + 3, plan.Up);
  const bool towards = plan.Mode == TOWARDS_POINT || plan.Mode == AWAY_FROM_POINT;
  if (towards && !(std::isfinite(plan.Point[0]) && std::isfinite(plan.Point[1]) && std::isfinite(plan.Point[2])))
  {
    vtkErrorMacro("OrientationPoint " << Triple(plan.Point) << " must be finite (" << (plan.Mode == TOWARDS_POINT ?
                  "TOWARDS_POINT" : "AWAY_FROM_POINT") << " orientation): the side of every normal is taken from it.");
    return false;
  }
  if (plan.Mode == UP || plan.Mode == UP_ALONG_SPANNING_TREE || plan.Mode == GROUND_UP_ALONG_SPANNING_TREE)
  {
    const double* u = plan.Up;
    const double length = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    if (!(length > 0.0) || !std::isfinite(length))
    {
      vtkErrorMacro("UpDirection " << Triple(u) << " must be a finite direction, not zero ("
                                   << (plan.Mode == UP ? "UP" : plan.Mode == UP_ALONG_SPANNING_TREE
                                         ? "UP_ALONG_SPANNING_TREE" : "GROUND_UP_ALONG_SPANNING_TREE")
                                   << " orientation).");
      return false;
    }
  }
  if (plan.Mode == AUTOMATIC)
  {
    this->ChooseOrientation(run, plan);
    return true;
  }
  switch (plan.Mode)
  {
    case NONE: plan.Report = "none (the eigen solver's sign)"; break;
    case TOWARDS_POINT: plan.Report = "towards the point " + Triple(plan.Point); break;
    case AWAY_FROM_POINT: plan.Report = "away from the point " + Triple(plan.Point); break;
    case MINIMUM_SPANNING_TREE: plan.Report = "minimum spanning tree, outward"; break;
    case AGREE_WITH_EXISTING: plan.Report = "agreeing with the existing normals"; break;
    case TOWARDS_VIEWPOINT_ARRAY: plan.Report = "towards each point's viewpoint (the viewpoint array)"; break;
    case UP: plan.Report = "up " + Triple(plan.Up) + ", point by point"; break;
    case UP_ALONG_SPANNING_TREE:
      plan.Report = "up " + Triple(plan.Up) + ", the walls along the minimum spanning tree";
      break;
    default: plan.Report = "minimum spanning tree, the ground or floor up " + Triple(plan.Up); break;
  }
  return true;
}

void vtkGLSNormalEstimation::ChooseOrientation(const vtkGLSRun& run, OrientationPlan& plan)
{
  vtkPointSet* input = run.Input;
  const vtkGLSDistributedCloud& dist = run.Distributed;
  const vtkIdType n = input->GetNumberOfPoints();
  vtkDataArray* scanners = input->GetPointData()->GetArray(vtkGLSArrayNames::ScannerPosition);
  const bool hasScanners = scanners && scanners->GetNumberOfComponents() == 3 && scanners->GetNumberOfTuples() == n &&
    (scanners->GetDataType() == VTK_FLOAT || scanners->GetDataType() == VTK_DOUBLE);
  const bool everyScanner = dist.AllTrue(hasScanners || n == 0) && dist.Sum(hasScanners ? 1.0 : 0.0) > 0.0;
  double sensor[3] = { 0.0, 0.0, 0.0 };
  vtkDataArray* fileSensor = input->GetFieldData()->GetArray(vtkGLSArrayNames::ScannerPosition);
  bool hasSensor = fileSensor && fileSensor->GetNumberOfComponents() == 3 && fileSensor->GetNumberOfTuples() == 1;
  if (hasSensor)
  {
    fileSensor->GetTuple(0, sensor);
    hasSensor = std::isfinite(sensor[0]) && std::isfinite(sensor[1]) && std::isfinite(sensor[2]);
  }
  hasSensor = dist.AllTrue(hasSensor);
  const std::vector<float> angle = ValuesNamed<float, vtkFloatArray>(input, vtkGLSArrayNames::ScanAngle);
  const std::vector<std::uint8_t> returns =
    ValuesNamed<std::uint8_t, vtkUnsignedCharArray>(input, vtkGLSArrayNames::NumberOfReturns);
  const std::vector<std::uint8_t> classes =
    ValuesNamed<std::uint8_t, vtkUnsignedCharArray>(input, vtkGLSArrayNames::Classification);
  std::vector<unsigned char> finite(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < finite.size(); ++i)
  {
    finite[i] = std::isfinite(run.Cloud.Points[3 * i]) ? 1 : 0; // a left-out row is NaN in all three
  }
  gls::LidarEvidence mine, all;
  gls::countLidarEvidence(angle.empty() ? nullptr : angle.data(), returns.empty() ? nullptr : returns.data(),
    classes.empty() ? nullptr : classes.data(), finite.data(), finite.size(), mine);
  // Summed over the pieces (a flag as a count: any piece that has the attribute).
  const auto sum = [&dist](double v) { return dist.Sum(v); };
  const auto any = [&dist](bool b) { return dist.Sum(b ? 1.0 : 0.0) > 0.0; };
  all.points = sum(mine.points);
  all.hasScanAngle = any(mine.hasScanAngle);
  all.nonZeroAngle = sum(mine.nonZeroAngle);
  all.angleBeyondSwath = sum(mine.angleBeyondSwath);
  all.hasReturns = any(mine.hasReturns);
  all.multipleReturns = sum(mine.multipleReturns);
  all.hasClasses = any(mine.hasClasses);
  all.ground = sum(mine.ground);
  const gls::OrientationChoice choice = gls::chooseOrientation(everyScanner, hasSensor ? sensor : nullptr, all);
  plan.Report = "automatic: " + choice.reason;
  switch (choice.source)
  {
    case gls::OrientationSource::ScannerPositions:
      plan.Mode = TOWARDS_VIEWPOINT_ARRAY;
      plan.ViewpointArray = vtkGLSArrayNames::ScannerPosition;
      break;
    case gls::OrientationSource::SensorPosition:
      plan.Mode = TOWARDS_POINT;
      std::copy(sensor, sensor + 3, plan.Point);
      break;
    case gls::OrientationSource::Airborne:
    case gls::OrientationSource::Terrestrial:
      plan.Mode = choice.source == gls::OrientationSource::Airborne ? UP_ALONG_SPANNING_TREE
                                                                    : GROUND_UP_ALONG_SPANNING_TREE;
      plan.Up[0] = plan.Up[1] = 0.0; // a lidar file's z is up
      plan.Up[2] = 1.0;
      break;
    default:
      plan.Mode = MINIMUM_SPANNING_TREE;
      break;
  }
}

void vtkGLSNormalEstimation::ResolveSettings(
  const vtkGLSRun& run, const OrientationPlan& plan, gls::NormalEstimationSettings& settings)
{
  // The core keeps the neighbourhoods' reach for the GLS refinement only, and the graph's degrees for the
  // orientation across pieces only.
  settings.reachWanted = this->Refinement == GLS_REFINEMENT;
  settings.graphDegreeWanted = run.Distributed.IsParallel();
  settings.neighborhood = this->NeighborhoodType == RADIUS ? gls::NeighborhoodType::Radius
                                                           : gls::NeighborhoodType::KNearest;
  settings.k = this->NumberOfNeighbors;
  settings.radius = this->Radius;
  switch (plan.Mode)
  {
    case NONE: settings.orientation = gls::NormalOrientation::None; break;
    case TOWARDS_POINT: settings.orientation = gls::NormalOrientation::TowardsPoint; break;
    case AWAY_FROM_POINT: settings.orientation = gls::NormalOrientation::AwayFromPoint; break;
    case MINIMUM_SPANNING_TREE: settings.orientation = gls::NormalOrientation::MinimumSpanningTree; break;
    case UP: settings.orientation = gls::NormalOrientation::Up; break;
    case UP_ALONG_SPANNING_TREE: settings.orientation = gls::NormalOrientation::UpAlongSpanningTree; break;
    case GROUND_UP_ALONG_SPANNING_TREE:
      settings.orientation = gls::NormalOrientation::GroundUpAlongSpanningTree;
      break;
    default: settings.orientation = gls::NormalOrientation::AgreeWithReference; break; // GatherReference's
  }
  const double* anchor = run.Cloud.Anchor; // the point in the cloud's coordinates
  settings.viewpoint = { plan.Point[0] - anchor[0], plan.Point[1] - anchor[1], plan.Point[2] - anchor[2] };
  settings.up = { plan.Up[0], plan.Up[1], plan.Up[2] };
  settings.graphNeighbors = this->GraphNeighbors;
  settings.minimumSpread = this->MinimumSpread;
  settings.maximumGrowth = this->MaximumGrowth;
  settings.parallel.threads = this->NumberOfThreads;
  settings.parallel.progress = [this](double f) { return this->ReportProgress(f, 0.0, 0.9); };
}

bool vtkGLSNormalEstimation::GatherReference(const vtkGLSRun& run, const OrientationPlan& plan,
  std::vector<double>& reference, gls::NormalEstimationSettings& settings)
{
  // AGREE_WITH_EXISTING follows the selected normals; TOWARDS_VIEWPOINT_ARRAY follows the directions from each point
  // to its viewpoint (the same rule: n . reference >= 0).
  if (plan.Mode != AGREE_WITH_EXISTING && plan.Mode != TOWARDS_VIEWPOINT_ARRAY)
  {
    return true;
  }
  vtkPointSet* input = run.Input;
  const vtkIdType n = input->GetNumberOfPoints();
  const vtkGLSDistributedCloud& dist = run.Distributed;
  const bool viewpoints = plan.Mode == TOWARDS_VIEWPOINT_ARRAY;
  std::string problem;
  bool absent = false;
  vtkDataArray* existing = nullptr;
  if (n > 0 && !plan.ViewpointArray.empty())
  {
    existing = input->GetPointData()->GetArray(plan.ViewpointArray.c_str()); // AUTOMATIC checked it
  }
  else if (n > 0 && viewpoints && !this->SelectedArrayName(1))
  {
    problem = "no viewpoint array is selected"; // no automatic choice: any 3-vector array could be taken
  }
  else if (n > 0)
  {
    existing = this->SelectNormals(viewpoints ? 1 : 0, input, problem, absent, viewpoints ? "viewpoint" : "normals");
  }
  if (!dist.AllTrue(existing || (dist.IsParallel() && n == 0)))
  {
    if (viewpoints)
    {
      vtkErrorMacro("TOWARDS_VIEWPOINT_ARRAY needs the scanner position of every point (a floating-point "
                    "3-component point array; select it with SetInputArrayToProcess(1, ...)): "
                    << (problem.empty() ? "another process has none" : problem) << ".");
    }
    else
    {
      vtkErrorMacro("AGREE_WITH_EXISTING needs existing normals (a floating-point 3-component point array with "
                    "one tuple per point; select it with SetInputArrayToProcess, or set active normals): "
                    << (problem.empty() ? "another process has none" : problem) << ".");
    }
    return false;
  }
  reference.resize(3 * static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    existing->GetTuple(i, &reference[3 * i]);
    for (int a = 0; viewpoints && a < 3; ++a)
    {
      // Towards the viewpoint, in the cloud's coordinates (from its anchor).
      reference[3 * i + a] = (reference[3 * i + a] - run.Cloud.Anchor[a]) - run.Cloud.Points[3 * i + a];
    }
  }
  settings.orientation = gls::NormalOrientation::AgreeWithReference;
  return true;
}

int vtkGLSNormalEstimation::EstimateSerial(vtkGLSRun& run, std::vector<double>& reference,
  gls::NormalEstimationSettings& settings, gls::NormalEstimationResult& result)
{
  this->MergeCoincidentPoints(run);
  if (run.Cloud.IsMerged() && !reference.empty())
  {
    reference = gls::mergedNormals(run.Cloud.Copies, reference.data());
  }
  settings.reference = reference.empty() ? nullptr : reference.data();
  if (this->NeighborhoodType == RADIUS && settings.radius == 0.0)
  {
    settings.radius = gls::medianKNearestDistance(
      run.Cloud.Points.data(), run.Cloud.Owned, this->NumberOfNeighbors, kAutomaticRadiusSamples);
    if (!(settings.radius > 0.0))
    {
      vtkErrorMacro("The automatic Radius is 0: the input has fewer than 2 distinct finite points.");
      return FAILED;
    }
  }
  if (this->FreesPointsEarly(run))
  {
    settings.pointsCopied = [&run] { run.Cloud.ReleaseCoordinates(); };
  }
  const bool completed = gls::estimateNormals(run.Cloud.Points.data(), run.Cloud.Owned, settings, result);
  settings.pointsCopied = nullptr;
  if (!completed)
  {
    return ABORTED; // the output is the input, without partial normals
  }
  gls::ParallelOptions refinement = settings.parallel;
  refinement.progress = [this](double f) { return this->ReportProgress(f, 0.9, 0.99); };
  if (this->Refinement == GLS_REFINEMENT &&
    !gls::refineNormalsByGls(run.Cloud.Points.data(), run.Cloud.Owned, result.reach, this->RefinementScale,
      result.normals.data(), refinement))
  {
    return ABORTED;
  }
  return COMPLETED;
}

bool vtkGLSNormalEstimation::FreesPointsEarly(const vtkGLSRun& run) const
{
  // Nothing reads a serial run's points after the core's grid is built, unless the GLS refinement does (a distributed
  // run's ghosts and refinement read them too): 24 bytes a point less at the estimation's peak.
  return !run.Distributed.IsParallel() && this->Refinement != GLS_REFINEMENT;
}

double vtkGLSNormalEstimation::NeededBytes(
  const vtkGLSRun& run, const gls::NormalEstimationSettings& settings, const std::vector<double>& reference) const
{
  // The larger of two moments: the core's peak beside this piece's copy of its points (made when the run began;
  // freed once the core's grid is built in a serial run without refinement, before the core's peak), and the
  // core's result beside the outputs (Normals and NormalQuality in their type, NormalNeighbors), which are made
  // once the core's grid and graph are gone. The reference normals are held throughout.
  const double n = static_cast<double>(run.Cloud.Owned);
  const double value = vtkGLSOutputPrecision::ValueBytes(this->OutputPrecision);
  const double points = this->FreesPointsEarly(run) ? 0.0 : n * 3.0 * sizeof(double);
  const double estimating = gls::normalEstimationBytes(run.Cloud.Owned, settings) + points;
  const double writing = gls::normalEstimationResultBytes(run.Cloud.Owned, settings) + points + n * (4.0 * value + 4.0);
  return std::max(estimating, writing) + static_cast<double>(reference.size()) * sizeof(double);
}

void vtkGLSNormalEstimation::WriteNormals(vtkGLSRun& run, const gls::NormalEstimationSettings& settings,
  const OrientationPlan& plan, const gls::NormalEstimationResult& result)
{
  const vtkIdType n = run.Input->GetNumberOfPoints();
  const vtkGLSDistributedCloud& dist = run.Distributed;
  // Doubles, or floats (OutputPrecision), each value converted from the double computed.
  const auto newArray = [&](const char* name, const std::vector<double>& values, int width) {
    using vtkGLSOutputPrecision::ValuesOf;
    const auto array = vtkGLSOutputPrecision::NewArray(name, n, width, this->OutputPrecision);
    if (vtkGLSOutputPrecision::IsSingle(this->OutputPrecision))
    {
      run.Cloud.ScatterToInput(values.data(), width, ValuesOf<float>(array));
    }
    else
    {
      run.Cloud.ScatterToInput(values.data(), width, ValuesOf<double>(array));
    }
    return array;
  };
  const vtkSmartPointer<vtkDataArray> normals = newArray(vtkGLSArrayNames::Normals, result.normals, 3);
  const vtkSmartPointer<vtkDataArray> quality = newArray(vtkGLSArrayNames::NormalQuality, result.spread, 1);
  vtkNew<vtkIntArray> neighbors;
  neighbors->SetName(vtkGLSArrayNames::NormalNeighbors);
  neighbors->SetNumberOfTuples(n);
  run.Cloud.ScatterToInput(result.neighborCounts.data(), 1, neighbors->GetPointer(0));
  vtkPointData* out = run.Output->GetPointData();
  out->SetNormals(normals);
  out->AddArray(quality);
  out->AddArray(neighbors);

  // One line for the points with finite coordinates that no neighbourhood gives a normal (every copy counted). A
  // fitted position is finite when it has a neighbourhood (itself at least); stray points and non-finite
  // coordinates have none.
  double undefined = 0.0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    // A merged copy's is its distinct position's.
    const std::size_t at = run.Cloud.IsMerged() ? run.Cloud.Copies.representative[static_cast<std::size_t>(i)]
                                                : static_cast<std::size_t>(i);
    const bool finite = result.neighborCounts[at] > 0;
    undefined += finite && !std::isfinite(result.normals[3 * at]) ? 1.0 : 0.0;
  }
  undefined = dist.Sum(undefined);
  const double total = dist.Sum(static_cast<double>(n));
  if (undefined > 0.0 && dist.GetRank() == 0)
  {
    vtkWarningMacro(<< static_cast<long long>(undefined) << " of the " << static_cast<long long>(total)
                    << " points have no normal (NaN): fewer than 3 neighbours, or neighbourhoods close to a line "
                       "(spread below MinimumSpread) even grown "
                    << this->MaximumGrowth << " times. See NormalQuality and NormalNeighbors.");
  }
  if (settings.neighborhood == gls::NeighborhoodType::Radius)
  {
    vtkNew<vtkDoubleArray> radius;
    radius->SetName(vtkGLSArrayNames::NormalRadius);
    radius->InsertNextValue(settings.radius);
    run.Output->GetFieldData()->AddArray(radius);
  }
  vtkNew<vtkStringArray> orientation;
  orientation->SetName(vtkGLSArrayNames::Orientation);
  orientation->InsertNextValue(plan.Report);
  run.Output->GetFieldData()->AddArray(orientation);
  this->WriteRunFieldData(run, run.Output->GetFieldData());
}

bool vtkGLSNormalEstimation::EstimateDistributed(vtkGLSRun& run, std::vector<double>& reference,
  gls::NormalEstimationSettings& settings, gls::NormalEstimationResult& result)
{
  const bool mst = gls::orientsAlongSpanningTree(settings.orientation);
  std::vector<int> degrees;
  return this->EstimateWithGhosts(run, reference, settings, result, degrees) &&
    (!mst || this->OrientAcrossPieces(run, settings, degrees, result));
}

bool vtkGLSNormalEstimation::EstimateWithGhosts(vtkGLSRun& run, std::vector<double>& reference,
  gls::NormalEstimationSettings& settings, gls::NormalEstimationResult& result, std::vector<int>& graphDegrees)
{
  const vtkGLSDistributedCloud& dist = run.Distributed;
  vtkGLSCloud& cloud = run.Cloud;
  const std::size_t n = cloud.Owned;
  // Ghosts: every point within the reach of this piece's neighbourhoods, grown as far as they may grow.
  const double reach = settings.neighborhood == gls::NeighborhoodType::Radius
    ? gls::reachableRadius(settings)
    : gls::kNearestReach(cloud.Points.data(), n, gls::reachableNeighbors(settings), settings.parallel);
  std::size_t ghostCount = 0;
  if (!dist.AllTrue(dist.AppendGhosts(cloud.Points, n, {}, reach, ghostCount)))
  {
    vtkErrorMacro("The exchange of ghost points between the processes failed.");
    return false;
  }
  run.GhostPoints = static_cast<long long>(ghostCount);
  this->MergeCoincidentPoints(run);
  if (!reference.empty())
  {
    reference.resize(3 * (n + ghostCount), std::numeric_limits<double>::quiet_NaN()); // ghosts: the solver's sign
    if (cloud.IsMerged())
    {
      reference = gls::mergedNormals(cloud.Copies, reference.data());
    }
    settings.reference = reference.data();
  }
  gls::NormalEstimationSettings local = settings;
  if (gls::orientsAlongSpanningTree(settings.orientation))
  {
    local.orientation = gls::NormalOrientation::None; // oriented over the whole cloud (OrientAcrossPieces)
  }
  local.parallel.progress = nullptr; // no abort half-way through a collective run
  gls::NormalEstimationResult estimate;
  gls::estimateNormals(cloud.Points.data(), cloud.Size(), local, estimate);
  const std::size_t owned = cloud.Owned; // distinct positions of this piece
  // (An array the settings did not want, such as the reach without the GLS refinement, stays empty.)
  const auto ownedPart = [owned](const auto& v, std::size_t width) {
    return std::vector<typename std::decay_t<decltype(v)>::value_type>(
      v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.empty() ? 0 : width * owned));
  };
  result.normals = ownedPart(estimate.normals, 3);
  result.neighborCounts = ownedPart(estimate.neighborCounts, 1);
  result.spread = ownedPart(estimate.spread, 1);
  result.reach = ownedPart(estimate.reach, 1);
  graphDegrees = ownedPart(estimate.graphDegree, 1);
  return true;
}

namespace
{

/// The columns of a row gathered for the distributed orientation: global id, position, unoriented normal, the
/// node's degree in the tree's graph.
constexpr int kOrientationColumns = 8;

/// Rank 0's orientation of every piece's rows (kOrientationColumns each) along one minimum spanning tree, in
/// global-id order (the serial order): the oriented normals, 3 per row in the rows' order.
std::vector<double> orientGatheredRows(const std::vector<double>& all, const gls::NormalEstimationSettings& settings,
  int threads, std::size_t& components)
{
  constexpr int W = kOrientationColumns;
  const std::size_t total = all.size() / W;
  std::vector<std::size_t> order(total);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(
    order.begin(), order.end(), [&all](std::size_t a, std::size_t b) { return all[W * a] < all[W * b]; });
  std::vector<double> sortedXyz(3 * total), sortedNormals(3 * total), sortedDegrees(total);
  for (std::size_t j = 0; j < total; ++j)
  {
    std::copy(&all[W * order[j] + 1], &all[W * order[j] + 4], &sortedXyz[3 * j]);
    std::copy(&all[W * order[j] + 4], &all[W * order[j] + 7], &sortedNormals[3 * j]);
    sortedDegrees[j] = all[W * order[j] + 7];
  }
  // A position held by several pieces is one node of the tree, as in a serial run.
  const gls::CoincidentPoints shared = gls::findCoincidentPoints(sortedXyz.data(), total, threads);
  std::vector<double> xyz = gls::distinctValues(shared, sortedXyz.data(), 3);
  std::vector<double> normals = gls::distinctValues(shared, sortedNormals.data(), 3);
  const std::vector<double> degreeValues = gls::distinctValues(shared, sortedDegrees.data(), 1);
  const std::vector<int> degrees(degreeValues.begin(), degreeValues.end());
  gls::orientByMinimumSpanningTree(xyz.data(), xyz.size() / 3, settings.graphNeighbors, normals.data(),
    settings.parallel, components, degrees.data(), settings.orientation, settings.up);
  gls::scatterToCopies(shared, normals.data(), 3, sortedNormals.data());
  std::vector<double> oriented(3 * total);
  for (std::size_t j = 0; j < total; ++j)
  {
    std::copy(&sortedNormals[3 * j], &sortedNormals[3 * j] + 3, &oriented[3 * order[j]]);
  }
  return oriented;
}

} // namespace

bool vtkGLSNormalEstimation::OrientAcrossPieces(const vtkGLSRun& run, const gls::NormalEstimationSettings& settings,
  const std::vector<int>& graphDegrees, gls::NormalEstimationResult& result)
{
  const vtkGLSDistributedCloud& dist = run.Distributed;
  const vtkGLSCloud& cloud = run.Cloud;
  const std::size_t owned = cloud.Owned;
  // Each distinct position of this piece goes with the global id of its first copy.
  const std::vector<long long> ids = dist.GlobalIds(run.Input);
  constexpr int W = kOrientationColumns;
  std::vector<double> rows(W * owned);
  for (std::size_t u = 0; u < owned; ++u)
  {
    rows[W * u] = static_cast<double>(ids[cloud.IsMerged() ? cloud.Copies.distinct[u] : u]);
    std::copy(&cloud.Points[3 * u], &cloud.Points[3 * u] + 3, &rows[W * u + 1]);
    std::copy(&result.normals[3 * u], &result.normals[3 * u] + 3, &rows[W * u + 4]);
    rows[W * u + 7] = static_cast<double>(graphDegrees[u]);
  }
  std::vector<double> all;
  std::vector<long long> counts;
  if (!dist.GatherRows(rows, W, 0, all, counts))
  {
    vtkErrorMacro("Gathering the points on rank 0 for the minimum-spanning-tree orientation failed.");
    return false;
  }
  const std::vector<double> oriented = dist.GetRank() == 0
    ? orientGatheredRows(all, settings, this->NumberOfThreads, result.components)
    : std::vector<double>();
  std::vector<double> mine;
  if (!dist.ScatterRows(oriented, 3, 0, counts, mine))
  {
    vtkErrorMacro("Sending the oriented normals back from rank 0 failed.");
    return false;
  }
  result.normals = mine;
  return true;
}

bool vtkGLSNormalEstimation::RefineDistributed(
  vtkGLSRun& run, const gls::ParallelOptions& parallelOptions, gls::NormalEstimationResult& result)
{
  const vtkGLSDistributedCloud& dist = run.Distributed;
  const std::size_t owned = run.Cloud.Owned; // distinct positions of this piece
  double largest = 0.0;
  for (std::size_t u = 0; u < owned; ++u)
  {
    largest = std::isfinite(result.reach[u]) ? std::max(largest, result.reach[u]) : largest;
  }
  std::vector<double> points(run.Cloud.Points.begin(), run.Cloud.Points.begin() + static_cast<std::ptrdiff_t>(3 * owned));
  std::vector<double> normals = result.normals;
  std::size_t ghostCount = 0;
  if (!dist.AllTrue(dist.AppendGhosts(points, owned, { { &normals, 3 } }, this->RefinementScale * largest, ghostCount)))
  {
    vtkErrorMacro("The exchange of ghost points for the GLS refinement failed.");
    return false;
  }
  // A position held by several pieces counts once, as in a serial run (the owned copies come first, so each owned
  // point is its position's first copy); the ghosts are neighbours only (no reach: not refined).
  const std::size_t total = points.size() / 3;
  std::vector<double> reach(result.reach);
  reach.resize(total, std::numeric_limits<double>::quiet_NaN());
  const gls::CoincidentPoints shared = gls::findCoincidentPoints(points.data(), total, this->NumberOfThreads);
  const std::vector<double> xyz = gls::distinctValues(shared, points.data(), 3);
  std::vector<double> distinctNormals = gls::distinctValues(shared, normals.data(), 3);
  const std::vector<double> distinctReach = gls::distinctValues(shared, reach.data(), 1);
  gls::ParallelOptions parallel = parallelOptions;
  parallel.progress = nullptr; // no abort half-way through a collective run
  gls::refineNormalsByGls(
    xyz.data(), xyz.size() / 3, distinctReach, this->RefinementScale, distinctNormals.data(), parallel);
  for (std::size_t u = 0; u < owned; ++u)
  {
    const std::size_t d = static_cast<std::size_t>(shared.representative[u]);
    std::copy(&distinctNormals[3 * d], &distinctNormals[3 * d] + 3, &result.normals[3 * u]);
  }
  return true;
}

void vtkGLSNormalEstimation::DescribeSettings(std::vector<SettingRange>& settings)
{
  this->Superclass::DescribeSettings(settings);
  settings.push_back({ "NeighborhoodType", static_cast<double>(this->NeighborhoodType), static_cast<double>(K_NEAREST), static_cast<double>(RADIUS) });
  settings.push_back({ "NumberOfNeighbors", static_cast<double>(this->NumberOfNeighbors), static_cast<double>(3), static_cast<double>(100000) });
  settings.push_back({ "Refinement", static_cast<double>(this->Refinement), static_cast<double>(NO_REFINEMENT), static_cast<double>(GLS_REFINEMENT) });
  settings.push_back({ "RefinementScale", static_cast<double>(this->RefinementScale), static_cast<double>(0.5), static_cast<double>(10.0) });
  settings.push_back({ "MinimumSpread", static_cast<double>(this->MinimumSpread), static_cast<double>(0.0), static_cast<double>(1.0) });
  settings.push_back({ "MaximumGrowth", static_cast<double>(this->MaximumGrowth), static_cast<double>(1.0), static_cast<double>(64.0) });
  settings.push_back({ "Orientation", static_cast<double>(this->Orientation), static_cast<double>(NONE), static_cast<double>(GROUND_UP_ALONG_SPANNING_TREE) });
  settings.push_back({ "GraphNeighbors", static_cast<double>(this->GraphNeighbors), static_cast<double>(1), static_cast<double>(1000) });
  settings.push_back({ "OutputPrecision", static_cast<double>(this->OutputPrecision),
    static_cast<double>(vtkAlgorithm::SINGLE_PRECISION), static_cast<double>(vtkAlgorithm::DOUBLE_PRECISION) });
}

void vtkGLSNormalEstimation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NeighborhoodType: " << (this->NeighborhoodType == K_NEAREST ? "KNearest" : "Radius") << "\n";
  os << indent << "NumberOfNeighbors: " << this->NumberOfNeighbors << "\n";
  os << indent << "Radius: " << this->Radius << "\n";
  os << indent << "Orientation: " << this->Orientation << "\n";
  os << indent << "UpDirection: " << this->UpDirection[0] << ", " << this->UpDirection[1] << ", "
     << this->UpDirection[2] << "\n";
  os << indent << "OrientationPoint: " << this->OrientationPoint[0] << ", " << this->OrientationPoint[1] << ", "
     << this->OrientationPoint[2] << "\n";
  os << indent << "GraphNeighbors: " << this->GraphNeighbors << "\n";
  os << indent << "MinimumSpread: " << this->MinimumSpread << "\n";
  os << indent << "MaximumGrowth: " << this->MaximumGrowth << "\n";
  os << indent << "Refinement: " << (this->Refinement == GLS_REFINEMENT ? "GLS" : "None") << "\n";
  os << indent << "RefinementScale: " << this->RefinementScale << "\n";
  os << indent << "OutputPrecision: " << vtkGLSOutputPrecision::Name(this->OutputPrecision) << "\n";
}
