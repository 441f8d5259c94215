// vtkGLSPrincipalDirections: ridges and valleys on cylinders (exact and multi-resolution), no answer on a sphere, a
// fused run that stores nothing per scale, and the reuse of an upstream scale space's curvatures.
#include "FilterTestUtilities.h"

#include "vtkGLSPrincipalDirections.h"
#include "vtkGLSScaleSpace.h"

#include "vtkPointData.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace glstest;

namespace
{

/// Runs the filter at scales 3 to 5% of a unit radius (five of them), exactly or with the multi-resolution evaluation.
vtkSmartPointer<vtkPolyData> steadiest(const Cloud& c, bool multiresolution = false)
{
  vtkNew<vtkGLSPrincipalDirections> f;
  f->SetInputData(makePolyData(c));
  f->SetScaleUnitsToAbsolute();
  f->SetMinScale(0.03);
  f->SetMaxScale(0.05);
  f->SetNumberOfScales(5);
  f->SetEvaluation(multiresolution ? vtkGLSScaleFilterBase::EVALUATION_MULTIRESOLUTION
                                   : vtkGLSScaleFilterBase::EVALUATION_EXACT);
  f->Update();
  EXPECT_STREQ(f->GetLastEvaluationUsed(), multiresolution ? "Multiresolution" : "Exact");
  return f->GetPolyDataOutput();
}

} // namespace

TEST(PrincipalDirectionsFilter, CylindersAreRidgesOutsideAndValleysInside)
{
  const double deg = 3.14159265358979 / 180.0;
  for (int run = 0; run < 4; ++run)
  {
    const bool inward = run % 2 == 1, multiresolution = run >= 2;
    const Cloud c = cylinderPatch(1.0, 0.3, 0.3, 0.004, 4, inward);
    const vtkSmartPointer<vtkPolyData> out = steadiest(c, multiresolution);
    const auto scale = pointArray(out, "GLSStableDirectionScale"), rate = pointArray(out, "GLSDirectionTurnRate");
    const auto anisotropy = pointArray(out, "GLSAnisotropy"), shape = pointArray(out, "GLSStableShapeIndex");
    const auto direction = pointArray(out, "GLSStableDirection"), ridge = pointArray(out, "GLSRidgeValley");
    EXPECT_STREQ(out->GetPointData()->GetVectors()->GetName(), "GLSStableDirection");
    EXPECT_STREQ(out->GetPointData()->GetScalars()->GetName(), "GLSRidgeValley");
    long checked = 0;
    for (std::size_t i = 0; i < c.size(); i += 13)
    {
      const double u = std::atan2(c.points[3 * i + 1], c.points[3 * i]), z = c.points[3 * i + 2];
      if (std::abs(u) > 0.2 || std::abs(z) > 0.2)
      {
        continue;
      }
      EXPECT_GE(scale[i], 0.03);
      EXPECT_LE(scale[i], 0.05);
      EXPECT_LT(rate[i], 0.2); // radians per log t: the direction hardly turns on a cylinder
      EXPECT_GT(anisotropy[i], 0.9); // (1 - |k2|) / (1 + |k2|) with k2 within 0.03 of 0
      EXPECT_NEAR(shape[i], inward ? -0.5 : 0.5, 0.03);
      EXPECT_EQ(ridge[i], inward ? -1.0 : 1.0);
      // d1 goes around the cylinder (outward normals: k1 = 1/r) or along it (inward: k1 = 0, k2 = -1/r).
      EXPECT_LT(std::abs(direction[3 * i + 2]), inward ? 2.0 : std::sin(2.0 * deg));
      if (inward)
      {
        EXPECT_GT(std::abs(direction[3 * i + 2]), std::cos(2.0 * deg));
      }
      ++checked;
    }
    EXPECT_GT(checked, 100) << inward << multiresolution;
  }
}

TEST(PrincipalDirectionsFilter, ASphereHasNoSteadiestDirection)
{
  const Cloud c = sphere(60000, 1.0); // about 13 points in the smallest ball
  const vtkSmartPointer<vtkPolyData> out = steadiest(c);
  for (const char* name : { "GLSStableDirectionScale", "GLSAnisotropy", "GLSRidgeValley" })
  {
    for (double v : pointArray(out, name))
    {
      ASSERT_TRUE(std::isnan(v)) << name;
    }
  }
}

TEST(PrincipalDirectionsFilter, StoresNothingPerScale)
{
  const Cloud c = sphere(150, 1.0);
  // 4,000 scales within 16 MiB: a stored scale space would need 100 MiB.
  vtkNew<vtkGLSPrincipalDirections> f;
  auto errors = catchErrors(f);
  f->SetInputData(makePolyData(c));
  f->SetScaleUnitsToAbsolute();
  f->SetMinScale(0.8);
  f->SetMaxScale(1.5);
  f->SetNumberOfScales(4000);
  f->SetMemoryBudget(16.0);
  f->Update();
  EXPECT_EQ(errors->Count, 0) << errors->Message;
  EXPECT_EQ(pointArray(f->GetPolyDataOutput(), "GLSRidgeValley").size(), c.size());
}

TEST(PrincipalDirectionsFilter, ReusesAnUpstreamScaleSpacesCurvatures)
{
  // Downstream of a GLS Scale Space that stored the curvatures, the reduction reads them back at its scales: the
  // same outputs as a fit at those scales, bit for bit (the arrays hold the doubles the fit gave). Without the arrays
  // (StorePrincipalCurvatures off upstream), it refits at its own scales.
  const Cloud c = cylinderPatch(1.0, 0.3, 0.3, 0.006, 5);
  vtkNew<vtkGLSScaleSpace> space;
  space->SetInputData(makePolyData(c));
  space->SetScaleUnitsToAbsolute();
  space->SetMinScale(0.03);
  space->SetMaxScale(0.06);
  space->SetNumberOfScales(4);
  space->StorePrincipalCurvaturesOn();
  vtkNew<vtkGLSPrincipalDirections> reused;
  reused->SetInputConnection(space->GetOutputPort());
  reused->SetScaleUnitsToAbsolute();
  reused->SetMinScale(0.02); // ignored: the upstream scales are used
  reused->SetMaxScale(0.03);
  reused->SetNumberOfScales(7);
  reused->Update();
  vtkNew<vtkGLSPrincipalDirections> fitted;
  fitted->SetInputData(makePolyData(c));
  fitted->SetScaleUnitsToAbsolute();
  fitted->SetMinScale(0.03);
  fitted->SetMaxScale(0.06);
  fitted->SetNumberOfScales(4);
  fitted->Update();
  EXPECT_EQ(fieldArray(reused->GetPolyDataOutput(), "GLSScales"), fieldArray(space->GetPolyDataOutput(), "GLSScales"));
  for (const char* name : { "GLSStableDirectionScale", "GLSDirectionTurnRate", "GLSAnisotropy", "GLSStableShapeIndex",
         "GLSStableDirection", "GLSRidgeValley" })
  {
    EXPECT_TRUE(identical(pointArray(reused->GetPolyDataOutput(), name), pointArray(fitted->GetPolyDataOutput(), name)))
      << name;
  }
  space->StorePrincipalCurvaturesOff();
  reused->Update();
  EXPECT_EQ(fieldArray(reused->GetPolyDataOutput(), "GLSScales").size(), 7u);
}
