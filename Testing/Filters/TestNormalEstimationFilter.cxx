// vtkGLSNormalEstimation: analytic sphere, the bunny scan against its mesh normals, bad input.
#include "FilterTestUtilities.h"

#include "vtkGLSNormalEstimation.h"

#include "vtkPointData.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace glstest;

TEST(NormalEstimationFilter, SphereNormalsPointOutward)
{
  const Cloud c = sphere(3000, 1.5, false, 0.3, 0.2, -0.1);
  vtkNew<vtkGLSNormalEstimation> f;
  f->SetInputData(makePolyData(c.points, {}));
  f->Update();
  vtkDataArray* n = f->GetOutput()->GetPointData()->GetNormals();
  ASSERT_NE(n, nullptr);
  EXPECT_STREQ(n->GetName(), "Normals");
  for (vtkIdType i = 0; i < n->GetNumberOfTuples(); ++i)
  {
    double v[3];
    n->GetTuple(i, v);
    ASSERT_GT(v[0] * c.normals[3 * i] + v[1] * c.normals[3 * i + 1] + v[2] * c.normals[3 * i + 2], 0.999) << i;
  }
}

TEST(NormalEstimationFilter, BunnyAgreesWithMeshNormals)
{
  auto mesh = bunnyMeshWithNormals();
  vtkDataArray* reference = mesh->GetPointData()->GetNormals();
  ASSERT_NE(reference, nullptr);
  for (int mode : { vtkGLSNormalEstimation::K_NEAREST, vtkGLSNormalEstimation::RADIUS })
  {
    vtkNew<vtkGLSNormalEstimation> f;
    f->SetInputData(bunnyCloud());
    f->SetNeighborhoodType(mode);
    f->SetRadius(0.004); // about 20 neighbours on this scan
    f->Update();
    vtkDataArray* n = f->GetOutput()->GetPointData()->GetNormals();
    ASSERT_EQ(n->GetNumberOfTuples(), reference->GetNumberOfTuples());
    vtkIdType agree = 0, defined = 0;
    for (vtkIdType i = 0; i < n->GetNumberOfTuples(); ++i)
    {
      double a[3], b[3];
      n->GetTuple(i, a);
      reference->GetTuple(i, b);
      if (std::isnan(a[0]) || b[0] * b[0] + b[1] * b[1] + b[2] * b[2] < 0.5)
      {
        continue; // undefined here, or a vertex no face uses (it has no mesh normal)
      }
      ++defined;
      agree += (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) > 0.0 ? 1 : 0;
    }
    EXPECT_GT(defined, n->GetNumberOfTuples() * 0.95) << "mode " << mode;
    EXPECT_GT(static_cast<double>(agree) / static_cast<double>(defined), 0.99) << "mode " << mode;
  }
}

TEST(NormalEstimationFilter, AgreeWithExistingAndViewpoint)
{
  const Cloud c = sphere(2000, 1.0);
  std::vector<double> inward(c.normals);
  for (double& v : inward)
  {
    v = -v;
  }
  vtkNew<vtkGLSNormalEstimation> f;
  f->SetInputData(makePolyData(c.points, inward));
  f->SetOrientationToAgreeWithExisting();
  f->Update();
  vtkDataArray* n = f->GetOutput()->GetPointData()->GetNormals();
  for (vtkIdType i = 0; i < n->GetNumberOfTuples(); i += 7)
  {
    double v[3];
    n->GetTuple(i, v);
    ASSERT_LT(v[0] * c.normals[3 * i] + v[1] * c.normals[3 * i + 1] + v[2] * c.normals[3 * i + 2], -0.999);
  }
  f->SetOrientationToTowardsPoint();
  f->SetOrientationPoint(0, 0, 0);
  f->Update();
  n = f->GetOutput()->GetPointData()->GetNormals();
  for (vtkIdType i = 0; i < n->GetNumberOfTuples(); i += 7)
  {
    double v[3];
    n->GetTuple(i, v);
    ASSERT_LT(v[0] * c.normals[3 * i] + v[1] * c.normals[3 * i + 1] + v[2] * c.normals[3 * i + 2], -0.999);
  }
}

TEST(NormalEstimationFilter, BadInputGivesClearErrors)
{
  vtkNew<vtkGLSNormalEstimation> f;
  auto errors = catchErrors(f);
  f->SetInputData(makePolyData(std::vector<double>{}, {}));
  f->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Message.find("no points"), std::string::npos) << errors->Message;

  const Cloud c = sphere(100, 1.0);
  f->SetInputData(makePolyData(c.points, {}));
  f->SetNeighborhoodTypeToRadius();
  f->SetRadius(-0.1); // 0 is the automatic radius (TestAdaptiveNormals)
  f->Update();
  EXPECT_EQ(errors->Count, 2);
  EXPECT_NE(errors->Message.find("Radius"), std::string::npos) << errors->Message;

  f->SetNeighborhoodTypeToKNearest();
  f->SetOrientationToAgreeWithExisting();
  f->Update();
  EXPECT_EQ(errors->Count, 3);
  EXPECT_NE(errors->Message.find("AGREE_WITH_EXISTING"), std::string::npos) << errors->Message;

  // A point or direction that is not finite names its property (it oriented nothing, silently, once).
  const double nan = std::numeric_limits<double>::quiet_NaN();
  f->SetOrientationToTowardsPoint();
  f->SetOrientationPoint(0.0, nan, 0.0);
  f->Update();
  EXPECT_EQ(errors->Count, 4);
  EXPECT_NE(errors->Message.find("OrientationPoint (0, nan, 0) must be finite"), std::string::npos) << errors->Message;
  EXPECT_EQ(f->GetOutput()->GetPointData()->GetNormals(), nullptr);
  f->SetOrientationToGroundUpAlongSpanningTree();
  f->SetUpDirection(nan, 0.0, 1.0);
  f->Update();
  EXPECT_EQ(errors->Count, 5);
  EXPECT_NE(errors->Message.find("UpDirection (nan, 0, 1) must be a finite direction"), std::string::npos)
    << errors->Message;
  // A viewpoint array that is not there is named as one (it was "the selected normals array").
  f->SetOrientationToTowardsViewpointArray();
  f->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Scanners");
  f->Update();
  EXPECT_EQ(errors->Count, 6);
  EXPECT_NE(errors->Message.find("the selected viewpoint array 'Scanners' is not a point array"), std::string::npos)
    << errors->Message;

  // Two points: too few neighbours, NaN normals, no error.
  f->SetOrientationToNone();
  f->SetInputData(makePolyData(std::vector<double>{ 0, 0, 0, 1, 0, 0 }, {}));
  f->Update();
  EXPECT_EQ(errors->Count, 6);
  EXPECT_TRUE(std::isnan(f->GetOutput()->GetPointData()->GetNormals()->GetComponent(0, 0)));
}

TEST(NormalEstimationFilter, UpFacesTheGivenDirectionAndRefusesNone)
{
  // A sphere faced point by point towards -z (any length), then a zero direction: an error, an empty output.
  const Cloud c = sphere(2000, 1.0);
  vtkNew<vtkGLSNormalEstimation> f;
  f->SetInputData(makePolyData(c.points, {}));
  f->SetOrientationToUp();
  f->SetUpDirection(0.0, 0.0, -3.0);
  f->Update();
  const std::vector<double> n = pointArray(f->GetPolyDataOutput(), "Normals");
  ASSERT_EQ(n.size(), 3 * c.size());
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    ASSERT_LE(n[3 * i + 2], 0.0) << "point " << i;
  }
  auto errors = catchErrors(f);
  f->SetUpDirection(0.0, 0.0, 0.0);
  f->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Message.find("UpDirection (0, 0, 0)"), std::string::npos) << errors->Message;
  EXPECT_EQ(f->GetPolyDataOutput()->GetNumberOfPoints(), 0);
}

TEST(NormalEstimationFilter, ANeedAboveTheMemoryBudgetIsRefusedBeforeAnyWork)
{
  // The estimation's need against MemoryBudget: the larger of the core's peak (gls::normalEstimationBytes, beside
  // the filter's copy of the points where it keeps it) and its result beside the outputs. The refusal names it; a
  // budget just above it runs, just below it is refused. At the defaults the core's peak is the larger, so float32
  // outputs need no less; the GLS refinement keeps the points and the reach (32 bytes a point more).
  const Cloud c = sphere(20000, 1.0);
  const auto neededMiB = [&](int precision, int refinement, double budget, bool& ran) {
    vtkNew<vtkGLSNormalEstimation> f;
    f->SetOutputPrecision(precision);
    f->SetRefinement(refinement);
    f->SetMemoryBudget(budget);
    f->SetInputData(makePolyData(c.points, {}));
    const auto errors = catchErrors(f.Get());
    f->Update();
    ran = f->GetOutput()->GetPointData()->GetArray("Normals") != nullptr;
    const std::string key = "the normal estimation needs about ";
    const std::size_t at = errors->Message.find(key);
    EXPECT_EQ(ran, at == std::string::npos) << errors->Message;
    return at == std::string::npos ? 0.0 : std::stod(errors->Message.substr(at + key.size()));
  };
  const double mib = 1024.0 * 1024.0;
  const int none = vtkGLSNormalEstimation::NO_REFINEMENT;
  bool ran = true;
  const double wide = neededMiB(vtkAlgorithm::DOUBLE_PRECISION, none, 0.01, ran);
  EXPECT_FALSE(ran);
  // About 141 bytes a point at the defaults (the grid, the estimates, the graph and the forest).
  EXPECT_GT(wide, 20000 * 120.0 / mib);
  EXPECT_LT(wide, 20000 * 180.0 / mib);
  neededMiB(vtkAlgorithm::DOUBLE_PRECISION, none, wide * 0.99, ran);
  EXPECT_FALSE(ran);
  neededMiB(vtkAlgorithm::DOUBLE_PRECISION, none, wide * 1.01, ran);
  EXPECT_TRUE(ran);
  EXPECT_NEAR(neededMiB(vtkAlgorithm::SINGLE_PRECISION, none, 0.01, ran), wide, 1e-3);
  const double refined = neededMiB(vtkAlgorithm::DOUBLE_PRECISION, vtkGLSNormalEstimation::GLS_REFINEMENT, 0.01, ran);
  EXPECT_NEAR(refined - wide, 20000 * 32.0 / mib, 1e-3);
}
