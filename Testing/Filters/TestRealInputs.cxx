// What users bring (Testing/README.md, "Real inputs"): colour arrays beside or instead of normals, failed filters
// in a pipeline, duplicate points, saturated features, silent clamps, unstructured grids and multiblocks.
#include "FilterTestUtilities.h"

#include "vtkGLSContinuousFeatures.h"
#include "vtkGLSGeometricVariation.h"
#include "vtkGLSMultiScaleDissimilarity.h"
#include "vtkGLSScaleSpace.h"
#include "vtkGLSScaleSpaceImage.h"

#include "vtkCellType.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace glstest;

namespace
{

vtkSmartPointer<vtkPolyData> runOn(vtkGLSFilterBase* f, vtkDataObject* input)
{
  f->SetInputData(input);
  f->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(vtkPolyData::SafeDownCast(f->GetOutputDataObject(0)));
  return out;
}

vtkSmartPointer<vtkDoubleArray> vectors(const char* name, const std::vector<double>& v)
{
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(3);
  a->SetNumberOfTuples(static_cast<vtkIdType>(v.size() / 3));
  std::copy(v.begin(), v.end(), a->GetPointer(0));
  return a;
}

std::vector<double> randomUnitVectors(std::size_t n, unsigned seed)
{
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  std::vector<double> v(3 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    double a[3] = { g(rng), g(rng), g(rng) };
    const double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int k = 0; k < 3; ++k)
    {
      v[3 * i + k] = a[k] / l;
    }
  }
  return v;
}

double quantile(std::vector<double> v, double q)
{
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return std::isnan(x); }), v.end());
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

} // namespace

TEST(RealInputs, ColoursAreNeverTakenAsNormals)
{
  // A coloured cloud without normals: RGB (unsigned char, 3 components) is no candidate.
  const Cloud c = sphere(2000, 1.0);
  auto pd = makePolyData(c.points, {});
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("RGB");
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(2000);
  rgb->Fill(200);
  pd->GetPointData()->AddArray(rgb);
  vtkNew<vtkGLSContinuousFeatures> f;
  auto errors = catchErrors(f);
  auto out = runOn(f, pd);
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Message.find("has no normals"), std::string::npos) << errors->Message;
  EXPECT_EQ(out->GetNumberOfPoints(), 0); // a failed filter gives an empty output

  // Selected by name, the colours are refused too.
  vtkNew<vtkGLSContinuousFeatures> g;
  auto named = catchErrors(g);
  g->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "RGB");
  runOn(g, pd);
  EXPECT_EQ(named->Count, 1);
  EXPECT_NE(named->Message.find("holds unsigned char values"), std::string::npos) << named->Message;
}

TEST(RealInputs, WithoutActiveNormalsTheArrayNamedAsNormalsIsUsedAndSeveralCandidatesAreAnError)
{
  const Cloud c = sphere(2000, 1.0);
  auto reference = makePolyData(c);
  vtkNew<vtkGLSContinuousFeatures> expected;
  const std::vector<double> want = pointArray(runOn(expected, reference), "GLSFeature");

  // Velocity listed first, nrm second, neither active: nrm, whose name says normals, is used.
  auto pd = makePolyData(c.points, {});
  pd->GetPointData()->AddArray(vectors("Velocity", randomUnitVectors(2000, 3)));
  pd->GetPointData()->AddArray(vectors("nrm", c.normals));
  vtkNew<vtkGLSContinuousFeatures> f;
  auto errors = catchErrors(f);
  EXPECT_TRUE(identical(pointArray(runOn(f, pd), "GLSFeature"), want));
  EXPECT_EQ(errors->Count, 0) << errors->Message;

  // Two candidates and no name saying normals: an error naming both.
  auto ambiguous = makePolyData(c.points, {});
  ambiguous->GetPointData()->AddArray(vectors("Velocity", randomUnitVectors(2000, 3)));
  ambiguous->GetPointData()->AddArray(vectors("Direction", c.normals));
  vtkNew<vtkGLSContinuousFeatures> g;
  auto several = catchErrors(g);
  EXPECT_EQ(runOn(g, ambiguous)->GetNumberOfPoints(), 0);
  EXPECT_EQ(several->Count, 1);
  EXPECT_NE(several->Message.find("'Velocity', 'Direction'"), std::string::npos) << several->Message;
}

TEST(RealInputs, NormalsFarFromUnitLengthGiveAWarningWithTheCount)
{
  Cloud c = sphere(2000, 1.0);
  auto unit = makePolyData(c);
  for (std::size_t i = 0; i < 300; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      c.normals[3 * i + k] *= 150.0; // e.g. colours in 0-255 stored as floats
    }
  }
  vtkNew<vtkGLSScaleSpace> a, b;
  a->SetMinScale(0.05); // every fit defined on this sphere: no other warning
  b->SetMinScale(0.05);
  auto warnings = vtkSmartPointer<ErrorCatcher>::New();
  b->AddObserver(vtkCommand::WarningEvent, warnings);
  const auto ka = pointArray(runOn(a, unit), "GLSKappa");
  const auto kb = pointArray(runOn(b, makePolyData(c)), "GLSKappa");
  EXPECT_EQ(warnings->Count, 1);
  EXPECT_NE(warnings->Message.find("300 normals of 'Normals' have lengths far from 1"), std::string::npos)
    << warnings->Message;
  ASSERT_EQ(ka.size(), kb.size());
  for (std::size_t i = 0; i < ka.size(); ++i)
  {
    ASSERT_TRUE((std::isnan(ka[i]) && std::isnan(kb[i])) || std::abs(ka[i] - kb[i]) <= 1e-12 * std::abs(ka[i]));
  }
}

TEST(RealInputs, AFailedFilterGivesAnEmptyOutputSoNothingDownstreamComputes)
{
  const Cloud c = sphere(2000, 1.0);
  vtkNew<vtkPolyData> input;
  input->ShallowCopy(makePolyData(c));
  vtkNew<vtkGLSScaleSpace> scales;
  scales->SetNumberOfScales(0);
  scales->SetInputData(input);
  auto first = catchErrors(scales);
  vtkNew<vtkGLSContinuousFeatures> features;
  features->SetInputConnection(scales->GetOutputPort());
  auto second = catchErrors(features);
  features->Update();
  EXPECT_EQ(first->Count, 1);
  EXPECT_NE(first->Message.find("scales"), std::string::npos) << first->Message;
  EXPECT_EQ(scales->GetOutput()->GetNumberOfPoints(), 0);
  // The pipeline does not run the downstream filter on a failed input; if it ran, an empty input is an error.
  EXPECT_EQ(features->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(features->GetOutput()->GetPointData()->GetArray("GLSFeature"), nullptr);
  EXPECT_TRUE(second->Count == 0 || second->Message.find("no points") != std::string::npos) << second->Message;
}

TEST(RealInputs, CoincidentPointsAreCountedOnceAndEveryCopyGetsTheResults)
{
  // The cloud, then copies of some of its points appended (as a reader that splits vertices per face corner
  // would): every copy's results are bitwise those of its original in the cloud without copies.
  const Cloud c = paraboloid(60, 1.0, 0.3, -0.2, 0.01, 0.02, 7);
  Cloud copies = c;
  std::mt19937_64 rng(11);
  std::vector<std::size_t> original;
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    for (int k = static_cast<int>(rng() % 4); k > 0; --k)
    {
      original.push_back(i);
    }
  }
  for (std::size_t i : original)
  {
    copies.add(c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2], c.normals[3 * i], c.normals[3 * i + 1],
      c.normals[3 * i + 2]);
  }
  for (int which = 0; which < 2; ++which)
  {
    vtkSmartPointer<vtkGLSScaleFilterBase> a, b;
    const char* name = which == 0 ? "GLSKappa" : "GLSFeature";
    if (which == 0)
    {
      a = vtkSmartPointer<vtkGLSScaleSpace>::New();
      b = vtkSmartPointer<vtkGLSScaleSpace>::New();
    }
    else
    {
      // An absolute sigma: the data-relative one is chosen from a sample of points, copies included.
      auto fa = vtkSmartPointer<vtkGLSContinuousFeatures>::New();
      auto fb = vtkSmartPointer<vtkGLSContinuousFeatures>::New();
      fa->SetSigmaModeToAbsolute();
      fb->SetSigmaModeToAbsolute();
      a = fa;
      b = fb;
    }
    auto warnings = vtkSmartPointer<ErrorCatcher>::New();
    b->AddObserver(vtkCommand::WarningEvent, warnings);
    const auto plain = runOn(a, makePolyData(c));
    const auto merged = runOn(b, makePolyData(copies));
    const std::vector<double> va = pointArray(plain, name), vb = pointArray(merged, name);
    const std::size_t width = va.size() / c.size();
    ASSERT_EQ(vb.size(), width * copies.size());
    for (std::size_t i = 0; i < copies.size(); ++i)
    {
      const std::size_t o = i < c.size() ? i : original[i - c.size()];
      for (std::size_t k = 0; k < width; ++k)
      {
        ASSERT_TRUE(identical({ vb[i * width + k] }, { va[o * width + k] })) << name << " point " << i;
      }
    }
    EXPECT_EQ(fieldArray(merged, "GLSCoincidentPoints"), std::vector<double>{ double(original.size()) });
    EXPECT_NE(warnings->Message.find(std::to_string(original.size()) + " of the " +
                std::to_string(copies.size()) + " input points coincide"),
      std::string::npos)
      << warnings->Message;
  }
}

TEST(RealInputs, DataRelativeSigmaKeepsTheBackgroundLowOnTheBundledMeshes)
{
  // The default sigma is chosen so that the median feature is 0.28; the 95th percentile measures the contrast.
  // Target of the issue: median <= 0.3 and p95 >= 0.6. The rocker arm (a CAD part where most points are near an
  // edge at the coarse scales) cannot have both with one sigma: at a median of 0.30 its p95 is 0.598.
  const struct
  {
    const char* File;
    double MinimumP95;
  } meshes[] = { { "stanford-bunny.obj", 0.6 }, { "spot.obj", 0.6 }, { "cheburashka.obj", 0.6 },
    { "fandisk.obj", 0.6 }, { "rocker-arm.obj", 0.55 } };
  for (const auto& m : meshes)
  {
    vtkNew<vtkGLSContinuousFeatures> f;
    const auto out = runOn(f, meshWithNormals(m.File));
    const std::vector<double> feature = pointArray(out, "GLSFeature");
    const double median = quantile(feature, 0.5), p95 = quantile(feature, 0.95);
    EXPECT_LE(median, 0.3) << m.File;
    EXPECT_GE(median, 0.26) << m.File;
    EXPECT_GE(p95, m.MinimumP95) << m.File;
    const std::vector<double> sigma = fieldArray(out, "GLSSigma");
    ASSERT_EQ(sigma.size(), 1u);
    EXPECT_EQ(sigma[0], f->GetLastSigma());
    EXPECT_GT(sigma[0], 0.1) << m.File; // the absolute default saturated these meshes
  }
  // A sphere stays featureless (nu is rounding noise there; sigma never goes below 1e-3).
  vtkNew<vtkGLSContinuousFeatures> s;
  const auto sphereOut = runOn(s, makePolyData(sphere(5000, 1.0)));
  for (double v : pointArray(sphereOut, "GLSFeature"))
  {
    ASSERT_LT(v, 1e-9);
  }
  EXPECT_EQ(fieldArray(sphereOut, "GLSSigma"), std::vector<double>{ 1e-3 });
  // The absolute sigma stays available.
  vtkNew<vtkGLSContinuousFeatures> absolute;
  absolute->SetSigmaModeToAbsolute();
  absolute->SetSigma(0.1);
  EXPECT_EQ(fieldArray(runOn(absolute, bunnyMeshWithNormals()), "GLSSigma"), std::vector<double>{ 0.1 });
}

TEST(RealInputs, InvalidParametersAreErrorsNamingThePropertyInsteadOfSilentClamps)
{
  const auto input = makePolyData(sphere(2000, 1.0));
  const auto expectError = [&](vtkGLSFilterBase* f, const char* what) {
    auto errors = catchErrors(f);
    const auto out = runOn(f, input);
    EXPECT_EQ(errors->Count, 1) << what;
    EXPECT_NE(errors->Message.find(what), std::string::npos) << errors->Message;
    EXPECT_EQ(out->GetNumberOfPoints(), 0) << what;
  };
  vtkNew<vtkGLSScaleSpace> one;
  one->SetMinimumNeighbors(1);
  expectError(one, "MinimumNeighbors must be 0 (automatic) or at least 3");
  vtkNew<vtkGLSContinuousFeatures> negative;
  negative->SetWEta(-1.0);
  expectError(negative, "WEta must be a finite weight >= 0");
  vtkNew<vtkGLSGeometricVariation> zero;
  zero->SetWTau(0.0);
  zero->SetWEta(0.0);
  zero->SetWKappa(0.0);
  expectError(zero, "are all 0");
  vtkNew<vtkGLSContinuousFeatures> target;
  target->SetTargetMedianFeature(1.0);
  expectError(target, "TargetMedianFeature must be strictly between 0 and 1");
}

TEST(RealInputs, ScalesWhereMostFitsAreUndefinedGiveOneWarningWithTheMedianNeighbourCount)
{
  vtkNew<vtkGLSContinuousFeatures> f;
  f->AddScale(1e-9);
  f->AddScale(0.02);
  auto warnings = vtkSmartPointer<ErrorCatcher>::New();
  f->AddObserver(vtkCommand::WarningEvent, warnings);
  runOn(f, makePolyData(sphere(2000, 1.0)));
  EXPECT_EQ(warnings->Count, 1) << warnings->Message;
  EXPECT_NE(warnings->Message.find("At 2 of the 2 scales"), std::string::npos) << warnings->Message;
  EXPECT_NE(warnings->Message.find("median neighbour count there is 1"), std::string::npos) << warnings->Message;

  vtkNew<vtkGLSContinuousFeatures> fine; // scales above the spacing: no warning
  fine->SetMinScale(0.03);
  auto none = vtkSmartPointer<ErrorCatcher>::New();
  fine->AddObserver(vtkCommand::WarningEvent, none);
  runOn(fine, makePolyData(sphere(20000, 1.0)));
  EXPECT_EQ(none->Count, 0) << none->Message;
}

TEST(RealInputs, AnUnstructuredGridGivesAnUnstructuredGridWithTheSameArrays)
{
  const Cloud c = paraboloid(50, 1.0, 0.3, -0.2, 0.005, 0.01, 3);
  auto pd = makePolyData(c);
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(pd->GetPoints());
  grid->GetPointData()->ShallowCopy(pd->GetPointData());
  grid->Allocate(static_cast<vtkIdType>(c.size()));
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(c.size()); ++i)
  {
    grid->InsertNextCell(VTK_VERTEX, 1, &i);
  }
  vtkNew<vtkGLSGeometricVariation> a, b;
  const auto fromPolyData = runOn(a, pd);
  b->SetInputData(grid);
  b->Update();
  auto* out = vtkUnstructuredGrid::SafeDownCast(b->GetOutputDataObject(0));
  ASSERT_NE(out, nullptr);
  EXPECT_EQ(out->GetNumberOfCells(), static_cast<vtkIdType>(c.size()));
  EXPECT_TRUE(identical(values(out->GetPointData()->GetArray("GLSGeometricVariation")),
    pointArray(fromPolyData, "GLSGeometricVariation")));
}

TEST(RealInputs, AMultiblockUsesTheWholeDiagonalAndOneQueryPoint)
{
  // Two spheres side by side, radii 1 and 2: relative scales are fractions of the diagonal of both.
  const Cloud small = sphere(3000, 1.0), big = sphere(6000, 2.0, false, 6.0, 0.0, 0.0);
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetBlock(0, makePolyData(small));
  blocks->SetBlock(1, makePolyData(big));
  // The diagonal of the box of both clouds' points (about [-1, 8] x [-2, 2] x [-2, 2]).
  double lo[3] = { 1e300, 1e300, 1e300 }, hi[3] = { -1e300, -1e300, -1e300 };
  for (const Cloud* c : { &small, &big })
  {
    for (std::size_t i = 0; i < c->points.size(); ++i)
    {
      lo[i % 3] = std::min(lo[i % 3], c->points[i]);
      hi[i % 3] = std::max(hi[i % 3], c->points[i]);
    }
  }
  const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
    (hi[2] - lo[2]) * (hi[2] - lo[2]));

  vtkNew<vtkGLSMultiScaleDissimilarity> f;
  f->SetMinScale(0.03);
  f->SetMaxScale(0.1);
  f->SetNumberOfScales(5);
  f->SetQueryPointId(3000 + 17); // point 17 of the second block
  auto errors = catchErrors(f);
  f->SetInputData(blocks);
  f->Update();
  ASSERT_EQ(errors->Count, 0) << errors->Message;
  auto* out = vtkMultiBlockDataSet::SafeDownCast(f->GetOutputDataObject(0));
  ASSERT_NE(out, nullptr);
  auto* first = vtkPolyData::SafeDownCast(out->GetBlock(0));
  auto* second = vtkPolyData::SafeDownCast(out->GetBlock(1));
  ASSERT_TRUE(first && second);
  const std::vector<double> scales = fieldArray(first, "GLSScales");
  ASSERT_EQ(scales.size(), 5u);
  EXPECT_NEAR(scales.front(), 0.03 * diagonal, 1e-12);
  EXPECT_EQ(fieldArray(second, "GLSScales"), scales);
  EXPECT_EQ(fieldArray(first, "GLSQueryPointId"), std::vector<double>{ 3017.0 });
  EXPECT_EQ(fieldArray(second, "GLSQueryPointId"), std::vector<double>{ 3017.0 });
  // Oracle: on exact spheres tau = 0 and phi = 1, so Delta = mean over the scales of (t/r - t/R)^2 between
  // spheres of radii r and R (the box prior over every scale), and 0 on the query's own sphere.
  double expected = 0.0;
  for (double t : scales)
  {
    expected += (t / 1.0 - t / 2.0) * (t / 1.0 - t / 2.0) / static_cast<double>(scales.size());
  }
  for (double d : pointArray(first, "GLSDissimilarity"))
  {
    ASSERT_NEAR(d, expected, 1e-9 * expected);
  }
  for (double d : pointArray(second, "GLSDissimilarity"))
  {
    ASSERT_LT(d, 1e-20);
  }

  // The features of a block equal those of the block alone at the same absolute scales.
  vtkNew<vtkGLSContinuousFeatures> whole, alone;
  whole->SetSigmaModeToAbsolute();
  whole->SetInputData(blocks);
  whole->Update();
  alone->SetSigmaModeToAbsolute();
  alone->SetScaleUnitsToAbsolute();
  for (double t : fieldArray(vtkPolyData::SafeDownCast(
         vtkMultiBlockDataSet::SafeDownCast(whole->GetOutputDataObject(0))->GetBlock(1)), "GLSScales"))
  {
    alone->AddScale(t);
  }
  EXPECT_TRUE(identical(
    pointArray(vtkPolyData::SafeDownCast(vtkMultiBlockDataSet::SafeDownCast(whole->GetOutputDataObject(0))->GetBlock(1)),
      "GLSFeature"),
    pointArray(runOn(alone, makePolyData(big)), "GLSFeature")));

  // A query id past the last block's points is an error naming the total.
  vtkNew<vtkGLSMultiScaleDissimilarity> bad;
  bad->SetQueryPointId(9000);
  auto badErrors = catchErrors(bad);
  bad->SetInputData(blocks);
  bad->Update();
  EXPECT_NE(badErrors->Message.find("9000 points in all"), std::string::npos) << badErrors->Message;
}

TEST(RealInputs, TheScaleSpaceImageRefusesASurface)
{
  vtkNew<vtkSphereSource> surface;
  surface->Update();
  vtkNew<vtkGLSScaleSpaceImage> f;
  auto errors = catchErrors(f);
  f->SetInputData(surface->GetOutput());
  f->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Message.find("is a surface"), std::string::npos) << errors->Message;
}

TEST(RealInputs, TheScaleSpaceHasAKappaSummaryThatColoursWhereSomeScalesAreUndefined)
{
  // A sparse sphere of radius 2: the finest scales hold too few neighbours (NaN there), the others give 1/2.
  vtkNew<vtkGLSScaleSpace> f;
  f->SetScaleUnitsToAbsolute();
  f->SetMinScale(0.01);
  f->SetMaxScale(1.0);
  const auto out = runOn(f, makePolyData(sphere(4000, 2.0)));
  const std::vector<double> kappa = pointArray(out, "GLSKappa");
  ASSERT_TRUE(std::any_of(kappa.begin(), kappa.end(), [](double v) { return std::isnan(v); }));
  const std::vector<double> median = pointArray(out, "GLSKappaMedian");
  ASSERT_EQ(median.size(), 4000u);
  for (double v : median)
  {
    ASSERT_NEAR(v, 0.5, 1e-12);
  }
  ASSERT_NE(out->GetPointData()->GetScalars(), nullptr);
  EXPECT_STREQ(out->GetPointData()->GetScalars()->GetName(), "GLSKappaMedian");
}
