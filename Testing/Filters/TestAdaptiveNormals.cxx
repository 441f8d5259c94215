// Normal estimation where the sampling is anisotropic or repeated: degenerate neighbourhoods grow or give NaN (counted),
// the automatic radius, coincident points merged, and the quality arrays. Oracles: the analytic normals of a sphere,
// a brute-force k-th neighbour distance, the same cloud without its copies, a mesh's own vertex normals, and the
// hit triangles of a simulated scanner (Testing/Benchmarks/ScannerSimulation.h).
#include "FilterTestUtilities.h"
#include "ScannerSimulation.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSContinuousFeatures.h"
#include "vtkGLSNormalEstimation.h"

#include "vtkCleanPolyData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkOBJReader.h"
#include "vtkPointData.h"
#include "vtkPolyDataNormals.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <random>

using namespace glstest;

namespace
{

constexpr double kDegree = 3.14159265358979323846 / 180.0;

/// ParaView's Sphere(ThetaResolution=120, PhiResolution=120): each latitude ring near a pole is far denser along
/// itself than the rings are apart. Points only (no normals).
vtkSmartPointer<vtkPolyData> uvSphere()
{
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(120);
  source->SetPhiResolution(120);
  source->SetRadius(0.5);
  source->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(source->GetOutput());
  out->GetPointData()->Initialize();
  return out;
}

/// Angle (degrees) between the estimated normal of point i and the radial direction (oriented: outward is 0).
double radialAngle(vtkPolyData* pd, vtkDataArray* normals, vtkIdType i)
{
  double p[3], n[3];
  pd->GetPoint(i, p);
  normals->GetTuple(i, n);
  const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  const double c = (p[0] * n[0] + p[1] * n[1] + p[2] * n[2]) / r;
  return std::acos(std::max(-1.0, std::min(1.0, c))) / kDegree;
}

/// A bundled mesh (Testing/Data) and its scan by the default simulated scanner with samplesAlong rays per line.
struct ScannedMesh
{
  vtkSmartPointer<vtkPolyData> Mesh;
  ScannerScan Scan;
};

ScannedMesh scanMesh(const std::string& file, int samplesAlong)
{
  vtkNew<vtkOBJReader> reader;
  reader->SetFileName(dataFile(file).c_str());
  reader->Update();
  ScannedMesh out;
  out.Mesh = reader->GetOutput();
  ScannerSettings settings;
  settings.SamplesAlong = samplesAlong;
  out.Scan = simulateScanner(out.Mesh, settings);
  return out;
}

} // namespace

TEST(AdaptiveNormals, UVSphereDefaultsAreWithinHalfADegreeAndFeaturesVanish)
{
  auto input = uvSphere();
  vtkNew<vtkGLSNormalEstimation> normals;
  normals->SetInputData(input);
  normals->Update();
  vtkPolyData* out = normals->GetPolyDataOutput();
  vtkDataArray* n = out->GetPointData()->GetNormals();
  ASSERT_NE(n, nullptr);
  double worst = 0.0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    worst = std::max(worst, radialAngle(out, n, i)); // NaN fails the comparison below
    ASSERT_TRUE(std::isfinite(n->GetComponent(i, 0))) << i;
  }
  EXPECT_LT(worst, 0.5);
  std::printf("UV sphere 120 x 120, defaults: worst normal %.3f degrees off radial\n", worst);
  // The quality arrays: the pole rings grew (more than 16 neighbours there), every spread at least MinimumSpread.
  vtkDataArray* quality = out->GetPointData()->GetArray(vtkGLSArrayNames::NormalQuality);
  vtkDataArray* used = out->GetPointData()->GetArray(vtkGLSArrayNames::NormalNeighbors);
  ASSERT_NE(quality, nullptr);
  ASSERT_NE(used, nullptr);
  double grown = 0.0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    EXPECT_GE(quality->GetComponent(i, 0), 0.05) << i;
    grown += used->GetComponent(i, 0) > 16 ? 1.0 : 0.0;
  }
  EXPECT_GT(grown, 0.0);

  vtkNew<vtkGLSContinuousFeatures> features;
  features->SetInputConnection(normals->GetOutputPort());
  features->Update();
  const std::vector<double> f = pointArray(features->GetPolyDataOutput(), vtkGLSArrayNames::Feature);
  ASSERT_EQ(f.size(), static_cast<std::size_t>(out->GetNumberOfPoints()));
  const double fMax = *std::max_element(f.begin(), f.end());
  const std::vector<double> sigma = fieldArray(features->GetPolyDataOutput(), vtkGLSArrayNames::Sigma);
  std::printf("UV sphere 120 x 120, defaults: largest feature %.4f (sigma %g)\n", fMax, sigma.at(0));
  // The data-relative sigma falls to its floor (1e-3) on a sphere, where nu hardly varies: still a low background.
  EXPECT_LT(fMax, 0.1);
  features->SetSigmaModeToAbsolute();
  features->SetSigma(0.1);
  features->Update();
  const std::vector<double> fa = pointArray(features->GetPolyDataOutput(), vtkGLSArrayNames::Feature);
  const double faMax = *std::max_element(fa.begin(), fa.end());
  std::printf("UV sphere 120 x 120, Sigma 0.1: largest feature %.4f\n", faMax);
  EXPECT_LT(faMax, 0.05);
}

TEST(AdaptiveNormals, UVSphereSmallRadiusIsCorrectOrNaNAndCounted)
{
  auto input = uvSphere();
  // Radius 0.05 (the case) and 0.02: near the equator a radius of 0.02 (on a sphere of radius 0.5: the
  // meridian spacing is 0.013, the rings' 0.026) holds three points of one meridian, whose PCA "normal" is the
  // tangent. Such neighbourhoods grow, or, without growth, give NaN and are counted.
  for (const auto& [r, maximumGrowth] : std::vector<std::pair<double, double>>{ { 0.05, 8.0 }, { 0.02, 8.0 }, { 0.02, 1.0 } })
  {
    vtkNew<vtkGLSNormalEstimation> normals;
    auto warnings = catchWarnings(normals);
    normals->SetNeighborhoodTypeToRadius();
    normals->SetRadius(r);
    normals->SetMaximumGrowth(maximumGrowth);
    normals->SetInputData(input);
    normals->Update();
    vtkPolyData* out = normals->GetPolyDataOutput();
    vtkDataArray* n = out->GetPointData()->GetNormals();
    ASSERT_NE(n, nullptr);
    long long nan = 0;
    double worst = 0.0;
    for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
    {
      if (!std::isfinite(n->GetComponent(i, 0)))
      {
        ++nan;
        continue;
      }
      worst = std::max(worst, radialAngle(out, n, i));
    }
    EXPECT_LT(worst, 5.0) << maximumGrowth;
    if (nan > 0)
    {
      ASSERT_EQ(warnings->Count, 1) << maximumGrowth;
      EXPECT_NE(warnings->Message.find(std::to_string(nan) + " of the "), std::string::npos) << warnings->Message;
    }
    if (maximumGrowth == 1.0)
    {
      EXPECT_GT(nan, 1000); // without growth the meridian triples have no normal (and are counted)
    }
    else
    {
      EXPECT_EQ(nan, 0);
    }
    const std::vector<double> radius = fieldArray(out, vtkGLSArrayNames::NormalRadius);
    ASSERT_EQ(radius.size(), 1u);
    EXPECT_EQ(radius[0], r);
    std::printf("UV sphere, Radius %g, MaximumGrowth %g: worst %.3f degrees, %lld NaN\n", r, maximumGrowth, worst, nan);
  }
}

TEST(AdaptiveNormals, AutomaticRadiusIsTheMedianKthNeighbourDistance)
{
  const Cloud c = sphere(3000, 1.0);
  vtkNew<vtkGLSNormalEstimation> normals;
  auto errors = catchErrors(normals);
  normals->SetNeighborhoodTypeToRadius();
  normals->SetNumberOfNeighbors(12);
  normals->SetInputData(makePolyData(c.points, {}));
  normals->Update();
  EXPECT_EQ(errors->Count, 0) << errors->Message;
  const std::vector<double> radius = fieldArray(normals->GetPolyDataOutput(), vtkGLSArrayNames::NormalRadius);
  ASSERT_EQ(radius.size(), 1u);
  // Brute force: the distance from every point to its 12th nearest (itself included), median.
  const std::size_t n = c.size();
  std::vector<double> kth;
  for (std::size_t i = 0; i < n; ++i)
  {
    std::vector<double> d(n);
    for (std::size_t j = 0; j < n; ++j)
    {
      const double dx = c.points[3 * i] - c.points[3 * j], dy = c.points[3 * i + 1] - c.points[3 * j + 1],
                   dz = c.points[3 * i + 2] - c.points[3 * j + 2];
      d[j] = std::sqrt(dx * dx + dy * dy + dz * dz);
    }
    std::nth_element(d.begin(), d.begin() + 11, d.end());
    kth.push_back(d[11]);
  }
  std::nth_element(kth.begin(), kth.begin() + n / 2, kth.end());
  EXPECT_NEAR(radius[0], kth[n / 2], 1e-12);
  // The normals it gives are radial.
  vtkDataArray* nrm = normals->GetPolyDataOutput()->GetPointData()->GetNormals();
  for (std::size_t i = 0; i < n; ++i)
  {
    const double dot = nrm->GetComponent(i, 0) * c.normals[3 * i] + nrm->GetComponent(i, 1) * c.normals[3 * i + 1] +
      nrm->GetComponent(i, 2) * c.normals[3 * i + 2];
    ASSERT_GT(dot, std::cos(5 * kDegree)) << i;
  }
  // Negative: an error naming the property.
  normals->SetRadius(-1.0);
  normals->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Message.find("Radius"), std::string::npos) << errors->Message;
}

TEST(AdaptiveNormals, CoincidentPointsAreMergedAndEveryCopyGetsTheNormal)
{
  // Every point repeated (1 to 3 copies, interleaved as an OBJ reader's per-corner vertices): the normals equal
  // those of the cloud without copies, bit for bit, orientation included.
  const Cloud c = sphere(4000, 1.0);
  std::vector<double> repeated;
  std::vector<std::size_t> source;
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    for (std::size_t copy = 0; copy <= i % 3; ++copy)
    {
      repeated.insert(repeated.end(), &c.points[3 * i], &c.points[3 * i] + 3);
      source.push_back(i);
    }
  }
  vtkNew<vtkGLSNormalEstimation> alone, copies;
  alone->SetInputData(makePolyData(c.points, {}));
  alone->Update();
  auto warnings = catchWarnings(copies);
  copies->SetInputData(makePolyData(repeated, {}));
  copies->Update();
  const std::vector<double> a = values(alone->GetPolyDataOutput()->GetPointData()->GetNormals());
  const std::vector<double> b = values(copies->GetPolyDataOutput()->GetPointData()->GetNormals());
  ASSERT_EQ(b.size(), 3 * source.size());
  for (std::size_t j = 0; j < source.size(); ++j)
  {
    for (int k = 0; k < 3; ++k)
    {
      ASSERT_EQ(b[3 * j + k], a[3 * source[j] + k]) << j;
    }
  }
  const long long merged = static_cast<long long>(source.size() - c.size());
  const std::vector<double> recorded = fieldArray(copies->GetPolyDataOutput(), vtkGLSArrayNames::CoincidentPoints);
  ASSERT_EQ(recorded.size(), 1u);
  EXPECT_EQ(recorded[0], static_cast<double>(merged));
  EXPECT_EQ(warnings->Count, 1);
  EXPECT_NE(warnings->Message.find(std::to_string(merged) + " of the "), std::string::npos) << warnings->Message;
}

TEST(AdaptiveNormals, SpotWithPerCornerVerticesMatchesItsMeshNormals)
{
  // spot.obj has texture coordinates: VTK's OBJ reader splits its 2,930 vertices per face corner. The normals of
  // the split cloud, compared with the cleaned mesh's vertex normals at the same positions.
  vtkNew<vtkOBJReader> reader;
  reader->SetFileName(dataFile("spot.obj").c_str());
  reader->Update();
  vtkPolyData* split = reader->GetOutput();
  ASSERT_GT(split->GetNumberOfPoints(), 10000);
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(reader->GetOutputPort());
  clean->PointMergingOn();
  clean->SetTolerance(0.0);
  vtkNew<vtkPolyDataNormals> meshNormals;
  meshNormals->SetInputConnection(clean->GetOutputPort());
  meshNormals->SplittingOff();
  meshNormals->ConsistencyOff();
  meshNormals->AutoOrientNormalsOff();
  meshNormals->Update();
  vtkPolyData* reference = meshNormals->GetOutput();
  std::map<std::array<double, 3>, vtkIdType> at;
  for (vtkIdType i = 0; i < reference->GetNumberOfPoints(); ++i)
  {
    double p[3];
    reference->GetPoint(i, p);
    at[{ p[0], p[1], p[2] }] = i;
  }

  auto points = vtkSmartPointer<vtkPolyData>::New();
  points->SetPoints(split->GetPoints());
  vtkNew<vtkGLSNormalEstimation> normals;
  normals->SetInputData(points);
  normals->Update();
  vtkDataArray* n = normals->GetPolyDataOutput()->GetPointData()->GetNormals();
  vtkDataArray* r = reference->GetPointData()->GetNormals();
  std::vector<double> angles;
  long long flipped = 0;
  for (vtkIdType i = 0; i < split->GetNumberOfPoints(); ++i)
  {
    double p[3], a[3], b[3];
    split->GetPoint(i, p);
    const auto found = at.find({ p[0], p[1], p[2] });
    ASSERT_NE(found, at.end()) << i;
    n->GetTuple(i, a);
    r->GetTuple(found->second, b);
    const double c = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    flipped += c < 0.0 ? 1 : 0;
    angles.push_back(std::acos(std::min(1.0, std::abs(c))) / kDegree);
  }
  std::nth_element(angles.begin(), angles.begin() + angles.size() / 2, angles.end());
  const double median = angles[angles.size() / 2];
  EXPECT_LT(median, 5.0);
  EXPECT_EQ(flipped, 0);
  std::printf("spot.obj split per corner (%lld points): median %.2f degrees, %lld flipped\n",
    static_cast<long long>(split->GetNumberOfPoints()), median, flipped);
}

TEST(AdaptiveNormals, TowardsViewpointArrayFacesEachPointsOwnScanner)
{
  // Half the points seen from outside (viewpoint 3 p), half from the centre (viewpoint 0): the normals face each
  // point's viewpoint, outward for the first half and inward for the second.
  const Cloud c = sphere(5000, 1.0);
  auto input = makePolyData(c.points, {});
  vtkNew<vtkDoubleArray> viewpoints;
  viewpoints->SetName("ScannerPosition");
  viewpoints->SetNumberOfComponents(3);
  viewpoints->SetNumberOfTuples(static_cast<vtkIdType>(c.size()));
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    const double f = i % 2 ? 0.0 : 3.0;
    viewpoints->SetTuple3(static_cast<vtkIdType>(i), f * c.points[3 * i], f * c.points[3 * i + 1], f * c.points[3 * i + 2]);
  }
  input->GetPointData()->AddArray(viewpoints);
  vtkNew<vtkGLSNormalEstimation> normals;
  auto errors = catchErrors(normals);
  normals->SetOrientationToTowardsViewpointArray();
  normals->SetInputData(input);
  normals->Update(); // no array selected: an error naming the mode
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Message.find("TOWARDS_VIEWPOINT_ARRAY"), std::string::npos) << errors->Message;
  normals->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "ScannerPosition");
  normals->Update();
  EXPECT_EQ(errors->Count, 1) << errors->Message;
  vtkDataArray* n = normals->GetPolyDataOutput()->GetPointData()->GetNormals();
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    const double dot = n->GetComponent(i, 0) * c.normals[3 * i] + n->GetComponent(i, 1) * c.normals[3 * i + 1] +
      n->GetComponent(i, 2) * c.normals[3 * i + 2];
    ASSERT_GT(i % 2 ? -dot : dot, 0.99) << i;
  }
}

TEST(AdaptiveNormals, GLSRefinementReducesTheErrorOnNoisyPositions)
{
  // A unit sphere whose points are moved along the radius by a Gaussian of 1% of the radius: the GLS refinement
  // (a sphere fit of the points and their PCA normals) brings the normals closer to radial than PCA alone.
  const Cloud c = sphere(20000, 1.0);
  std::vector<double> noisy = c.points;
  std::mt19937_64 random(3);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    const double e = noise(random);
    for (int a = 0; a < 3; ++a)
    {
      noisy[3 * i + a] += e * c.normals[3 * i + a];
    }
  }
  auto meanError = [&](bool refine) {
    vtkNew<vtkGLSNormalEstimation> normals;
    if (refine)
    {
      normals->SetRefinementToGLS();
    }
    normals->SetInputData(makePolyData(noisy, {}));
    normals->Update();
    vtkDataArray* n = normals->GetPolyDataOutput()->GetPointData()->GetNormals();
    double sum = 0.0;
    for (std::size_t i = 0; i < c.size(); ++i)
    {
      const double dot = n->GetComponent(i, 0) * c.normals[3 * i] + n->GetComponent(i, 1) * c.normals[3 * i + 1] +
        n->GetComponent(i, 2) * c.normals[3 * i + 2];
      sum += std::acos(std::min(1.0, dot)) / kDegree; // oriented: a flipped normal counts 180 degrees
    }
    return sum / static_cast<double>(c.size());
  };
  const double pca = meanError(false), refined = meanError(true);
  std::printf("noisy sphere: mean error %.2f degrees (PCA), %.2f (GLS refinement)\n", pca, refined);
  EXPECT_LT(refined, 0.8 * pca);
}

TEST(AdaptiveNormals, ScannerSamplingOfACADPartAwayFromCreases)
{
  // fandisk scanned from two positions, 10:1 denser along the scan lines: away from the creases the default normals
  // are within 5 degrees of the hit triangles' (turned to the scanner) far more often than the plain 16 nearest, and
  // facing each point's scanner orients all of them.
  const ScannedMesh fandisk = scanMesh("fandisk.obj", 600);
  const ScannerScan& scan = fandisk.Scan;
  ASSERT_GT(scan.Size(), 20000u);
  const std::vector<double> creases = distanceToCreases(fandisk.Mesh, scan, 30.0);
  const double margin = 0.01 * fandisk.Mesh->GetLength();
  auto input = scanAsPolyData(scan);
  auto score = [&](const std::function<void(vtkGLSNormalEstimation*)>& set, double& wrong) {
    vtkNew<vtkGLSNormalEstimation> normals;
    set(normals);
    normals->SetInputData(input);
    normals->Update();
    vtkDataArray* n = normals->GetPolyDataOutput()->GetPointData()->GetNormals();
    double counted = 0.0, within = 0.0;
    wrong = 0.0;
    for (std::size_t i = 0; i < scan.Size(); ++i)
    {
      if (!(creases[i] > margin))
      {
        continue;
      }
      counted += 1.0;
      const double* t = &scan.Normals[3 * i];
      const double dot = n->GetComponent(i, 0) * t[0] + n->GetComponent(i, 1) * t[1] + n->GetComponent(i, 2) * t[2];
      within += std::abs(dot) >= std::cos(5 * kDegree) ? 1.0 : 0.0;
      wrong += dot < 0.0 ? 1.0 : 0.0;
    }
    wrong /= counted;
    return within / counted;
  };
  double wrongDefault = 0, wrongBefore = 0, wrongViewpoint = 0, wrongAutomatic = 0;
  const double adaptive =
    score([](vtkGLSNormalEstimation* f) { f->SetOrientationToMinimumSpanningTree(); }, wrongDefault);
  const double before = score(
    [](vtkGLSNormalEstimation* f) {
      f->SetMaximumGrowth(1.0);
      f->SetMinimumSpread(0.0);
    },
    wrongBefore);
  score(
    [](vtkGLSNormalEstimation* f) {
      f->SetOrientationToTowardsViewpointArray();
      f->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "ScannerPosition");
    },
    wrongViewpoint);
  score([](vtkGLSNormalEstimation*) {}, wrongAutomatic); // the default, Automatic: the ScannerPosition array
  std::printf("fandisk scanned (%zu points): within 5 degrees %.1f%% (defaults), %.1f%% (no growth); wrong way "
              "%.2f%% (tree), %.2f%% (viewpoints)\n",
    scan.Size(), 100 * adaptive, 100 * before, 100 * wrongDefault, 100 * wrongViewpoint);
  EXPECT_GT(adaptive, 0.95); // measured 97.4%
  EXPECT_GT(adaptive, before + 0.1);
  // Facing the scanner can only miss at grazing hits whose estimate is off by more than the grazing angle.
  EXPECT_LT(wrongViewpoint, 5e-3); // measured 0.15%
  EXPECT_LT(wrongViewpoint, 0.5 * wrongDefault);
  EXPECT_EQ(wrongAutomatic, wrongViewpoint);
}

TEST(AdaptiveNormals, ScannedBunnyIsOrientedLikeTheFileByTheTree)
{
  // The bunny scanned from two positions: the tree's graph grows with the neighbourhoods (ten neighbours along a
  // scan line never reach the next line), so one consistent orientation covers the scan: the file's outward
  // winding at (almost) every point.
  const ScannerScan scan = scanMesh("stanford-bunny.obj", 1200).Scan;
  ASSERT_GT(scan.Size(), 30000u);
  vtkNew<vtkGLSNormalEstimation> normals;
  normals->SetInputData(scanAsPolyData(scan));
  normals->Update();
  vtkDataArray* n = normals->GetPolyDataOutput()->GetPointData()->GetNormals();
  double wrong = 0.0;
  for (std::size_t i = 0; i < scan.Size(); ++i)
  {
    const double* w = &scan.WoundNormals[3 * i];
    wrong += n->GetComponent(i, 0) * w[0] + n->GetComponent(i, 1) * w[1] + n->GetComponent(i, 2) * w[2] < 0.0 ? 1 : 0;
  }
  wrong /= static_cast<double>(scan.Size());
  std::printf("bunny scanned (%zu points): %.2f%% against the file's winding\n", scan.Size(), 100 * wrong);
  EXPECT_LT(wrong, 0.01);
}
