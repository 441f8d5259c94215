// vtkGLSPrincipalDirections: ridges and valleys on cylinders (exact and multi-resolution), no answer on a sphere, a
// fused run that stores nothing per scale, the reuse of an upstream scale space's curvatures, a chosen scale's
// directions, float32 outputs; and the same arrays from vtkGLSContinuousFeatures' fused pass (DirectionSummary).
#include "FilterTestUtilities.h"

#include "vtkGLSContinuousFeatures.h"
#include "vtkGLSPrincipalDirections.h"
#include "vtkGLSScaleSpace.h"

#include "vtkPointData.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <vector>

using namespace glstest;

namespace
{

/// The arrays of each point's steadiest direction (GLS Principal Directions, and the features' DirectionSummary).
const char* const kSteadiestArrays[] = { "GLSStableDirectionScale", "GLSDirectionTurnRate", "GLSAnisotropy",
  "GLSStableShapeIndex", "GLSStableDirection", "GLSRidgeValley" };

/// Sets `count` scales from `min` to `max`, lengths.
void setAbsoluteScales(vtkGLSScaleFilterBase* f, double min, double max, int count)
{
  f->SetScaleUnitsToAbsolute();
  f->SetMinScale(min);
  f->SetMaxScale(max);
  f->SetNumberOfScales(count);
}

/// GLS Scale Space of the cloud at four scales from 0.03 to 0.06, storing the principal curvatures.
vtkSmartPointer<vtkGLSScaleSpace> curvatureSpace(const Cloud& c)
{
  auto space = vtkSmartPointer<vtkGLSScaleSpace>::New();
  space->SetInputData(makePolyData(c));
  setAbsoluteScales(space, 0.03, 0.06, 4);
  space->StorePrincipalCurvaturesOn();
  return space;
}

/// Runs the filter at scales 3 to 5% of a unit radius (five of them), exactly or with the multi-resolution evaluation.
vtkSmartPointer<vtkPolyData> steadiest(const Cloud& c, bool multiresolution = false)
{
  vtkNew<vtkGLSPrincipalDirections> f;
  f->SetInputData(makePolyData(c));
  setAbsoluteScales(f, 0.03, 0.05, 5);
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
  setAbsoluteScales(f, 0.8, 1.5, 4000);
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
  const auto space = curvatureSpace(c);
  vtkNew<vtkGLSPrincipalDirections> reused;
  reused->SetInputConnection(space->GetOutputPort());
  setAbsoluteScales(reused, 0.02, 0.03, 7); // ignored: the upstream scales are used
  reused->Update();
  vtkNew<vtkGLSPrincipalDirections> fitted;
  fitted->SetInputData(makePolyData(c));
  setAbsoluteScales(fitted, 0.03, 0.06, 4);
  fitted->Update();
  EXPECT_EQ(fieldArray(reused->GetPolyDataOutput(), "GLSScales"), fieldArray(space->GetPolyDataOutput(), "GLSScales"));
  for (const char* name : kSteadiestArrays)
  {
    EXPECT_TRUE(identical(pointArray(reused->GetPolyDataOutput(), name), pointArray(fitted->GetPolyDataOutput(), name)))
      << name;
  }
  space->StorePrincipalCurvaturesOff();
  reused->Update();
  EXPECT_EQ(fieldArray(reused->GetPolyDataOutput(), "GLSScales").size(), 7u);
}

TEST(PrincipalDirectionsFilter, WritesTheCurvaturesOfAChosenScaleForGlyphs)
{
  // DirectionScale picks the analysed scale nearest to it (in log t): its k1, k2, d1 and d2 are the upstream scale
  // space's at that scale, bit for bit, and d1 becomes the active vectors. Off (0) by default; a scale outside the
  // analysed ones is refused with an error and an empty output.
  const Cloud c = cylinderPatch(1.0, 0.3, 0.3, 0.006, 6);
  const auto space = curvatureSpace(c);
  space->Update();
  const std::vector<double> scales = fieldArray(space->GetPolyDataOutput(), "GLSScales");
  ASSERT_EQ(scales.size(), 4u);
  vtkNew<vtkGLSPrincipalDirections> f;
  auto errors = catchErrors(f);
  f->SetInputConnection(space->GetOutputPort());
  f->Update();
  EXPECT_EQ(f->GetPolyDataOutput()->GetPointData()->GetArray("GLSK1AtScale"), nullptr);
  EXPECT_STREQ(f->GetPolyDataOutput()->GetPointData()->GetVectors()->GetName(), "GLSStableDirection");
  const std::size_t S = scales.size();
  const auto k1 = pointArray(space->GetPolyDataOutput(), "GLSK1"), k2 = pointArray(space->GetPolyDataOutput(), "GLSK2");
  const auto d1 = pointArray(space->GetPolyDataOutput(), "GLSPrincipalDirection1");
  const auto d2 = pointArray(space->GetPolyDataOutput(), "GLSPrincipalDirection2");
  const double diagonal = space->GetPolyDataOutput()->GetLength();
  for (std::size_t chosen : { std::size_t(0), std::size_t(2), std::size_t(3) })
  {
    // Absolute, 1% off the scale; then relative to the diagonal, 1% off the other way.
    for (int relative = 0; relative < 2; ++relative)
    {
      if (relative)
      {
        f->SetScaleUnitsToRelativeToDiagonal();
        f->SetDirectionScale(scales[chosen] * (chosen == 3 ? 1.0 : 1.01) / diagonal);
      }
      else
      {
        f->SetScaleUnitsToAbsolute();
        f->SetDirectionScale(scales[chosen] * (chosen == 0 ? 1.0 : 0.99));
      }
      f->Update();
      ASSERT_EQ(errors->Count, 0) << errors->Message;
      vtkPolyData* out = f->GetPolyDataOutput();
      EXPECT_EQ(fieldArray(out, "GLSDirectionScale"), std::vector<double>{ scales[chosen] });
      EXPECT_STREQ(out->GetPointData()->GetVectors()->GetName(), "GLSPrincipalDirection1AtScale");
      const auto ck1 = pointArray(out, "GLSK1AtScale"), ck2 = pointArray(out, "GLSK2AtScale");
      const auto cd1 = pointArray(out, "GLSPrincipalDirection1AtScale");
      const auto cd2 = pointArray(out, "GLSPrincipalDirection2AtScale");
      ASSERT_EQ(ck1.size(), c.size());
      ASSERT_EQ(cd2.size(), 3 * c.size());
      std::vector<double> wk1, wk2, wd1, wd2;
      for (std::size_t i = 0; i < c.size(); ++i)
      {
        wk1.push_back(k1[i * S + chosen]);
        wk2.push_back(k2[i * S + chosen]);
        for (int a = 0; a < 3; ++a)
        {
          wd1.push_back(d1[3 * (i * S + chosen) + a]);
          wd2.push_back(d2[3 * (i * S + chosen) + a]);
        }
      }
      EXPECT_TRUE(identical(ck1, wk1)) << chosen << relative;
      EXPECT_TRUE(identical(ck2, wk2)) << chosen << relative;
      EXPECT_TRUE(identical(cd1, wd1)) << chosen << relative;
      EXPECT_TRUE(identical(cd2, wd2)) << chosen << relative;
    }
  }
  f->SetScaleUnitsToAbsolute();
  for (double outside : { scales.front() * 0.98, scales.back() * 1.02 })
  {
    f->SetDirectionScale(outside);
    f->Update();
    EXPECT_EQ(errors->Count, 1) << outside;
    EXPECT_NE(errors->Message.find("outside the analysed scales"), std::string::npos) << errors->Message;
    EXPECT_EQ(f->GetPolyDataOutput()->GetNumberOfPoints(), 0);
    errors->Count = 0;
  }
}

TEST(PrincipalDirectionsFilter, SinglePrecisionWritesTheDoublesRounded)
{
  // OutputPrecision Single: every array float32, each value the float nearest the double the default run writes.
  const Cloud c = cylinderPatch(1.0, 0.3, 0.3, 0.008, 7);
  vtkNew<vtkGLSPrincipalDirections> f;
  f->SetInputData(makePolyData(c));
  setAbsoluteScales(f, 0.04, 0.06, 3);
  f->SetDirectionScale(0.05);
  f->Update();
  vtkNew<vtkPolyData> doubles;
  doubles->DeepCopy(f->GetPolyDataOutput());
  f->SetOutputPrecision(vtkAlgorithm::SINGLE_PRECISION);
  f->Update();
  int compared = 0;
  std::vector<const char*> names(std::begin(kSteadiestArrays), std::end(kSteadiestArrays));
  for (const char* chosen : { "GLSK1AtScale", "GLSK2AtScale", "GLSPrincipalDirection1AtScale",
         "GLSPrincipalDirection2AtScale" })
  {
    names.push_back(chosen);
  }
  for (const char* name : names)
  {
    EXPECT_EQ(doubles->GetPointData()->GetArray(name)->GetDataType(), VTK_DOUBLE) << name;
    EXPECT_EQ(f->GetPolyDataOutput()->GetPointData()->GetArray(name)->GetDataType(), VTK_FLOAT) << name;
    const auto wide = pointArray(doubles, name), narrow = pointArray(f->GetPolyDataOutput(), name);
    ASSERT_EQ(wide.size(), narrow.size()) << name;
    for (std::size_t i = 0; i < wide.size(); ++i)
    {
      EXPECT_TRUE(narrow[i] == static_cast<double>(static_cast<float>(wide[i])) ||
        (std::isnan(narrow[i]) && std::isnan(wide[i])))
        << name << " " << i;
    }
    ++compared;
  }
  EXPECT_EQ(compared, 10);
  f->SetOutputPrecision(7);
  auto errors = catchErrors(f);
  f->Update();
  EXPECT_EQ(errors->Count, 1);
}

TEST(PrincipalDirectionsFilter, TheFeaturesPassWritesTheSameDirectionsInOneFit)
{
  // GLS Continuous Features with ScaleSummary and DirectionSummary: the steadiest directions of GLS Principal
  // Directions at the same scales, bit for bit (the same fit of the curvatures), exact and multi-resolution, beside
  // the features and summary of the pass without them (the same sphere fit: equal to rounding, 1e-12 relative).
  const Cloud c = cylinderPatch(1.0, 0.3, 0.3, 0.006, 8);
  for (const bool multiresolution : { false, true })
  {
    const int evaluation = multiresolution ? vtkGLSScaleFilterBase::EVALUATION_MULTIRESOLUTION
                                           : vtkGLSScaleFilterBase::EVALUATION_EXACT;
    const auto configure = [&](vtkGLSScaleFilterBase* f) {
      f->SetInputData(makePolyData(c));
      setAbsoluteScales(f, 0.03, 0.06, 4);
      f->SetEvaluation(evaluation);
    };
    vtkNew<vtkGLSPrincipalDirections> directions;
    configure(directions);
    directions->Update();
    vtkNew<vtkGLSContinuousFeatures> plain, fused;
    for (vtkGLSContinuousFeatures* f : { plain.Get(), fused.Get() })
    {
      configure(f);
      f->ScaleSummaryOn();
    }
    fused->DirectionSummaryOn();
    plain->Update();
    fused->Update();
    EXPECT_STREQ(fused->GetLastEvaluationUsed(), multiresolution ? "Multiresolution" : "Exact");
    EXPECT_EQ(plain->GetPolyDataOutput()->GetPointData()->GetArray("GLSStableShapeIndex"), nullptr);
    EXPECT_STREQ(fused->GetPolyDataOutput()->GetPointData()->GetScalars()->GetName(), "GLSFeature");
    for (const char* name : kSteadiestArrays)
    {
      EXPECT_TRUE(identical(pointArray(fused->GetPolyDataOutput(), name),
        pointArray(directions->GetPolyDataOutput(), name)))
        << name << multiresolution;
    }
    long finite = 0;
    for (const char* name : { "GLSFeature", "GLSStableScale", "GLSStableKappa", "GLSMaxVariation" })
    {
      const auto a = pointArray(plain->GetPolyDataOutput(), name), b = pointArray(fused->GetPolyDataOutput(), name);
      ASSERT_EQ(a.size(), b.size()) << name;
      for (std::size_t i = 0; i < a.size(); ++i)
      {
        if (std::isnan(a[i]))
        {
          EXPECT_TRUE(std::isnan(b[i])) << name << " " << i;
          continue;
        }
        EXPECT_NEAR(b[i], a[i], 1e-12 * std::max(1.0, std::abs(a[i]))) << name << " " << i;
        ++finite;
      }
    }
    EXPECT_GT(finite, 1000);
  }
  // DirectionSummary without ScaleSummary: refused, not ignored.
  vtkNew<vtkGLSContinuousFeatures> alone;
  auto errors = catchErrors(alone);
  alone->SetInputData(makePolyData(c));
  alone->DirectionSummaryOn();
  alone->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Message.find("turn ScaleSummary on"), std::string::npos) << errors->Message;
  EXPECT_EQ(alone->GetPolyDataOutput()->GetNumberOfPoints(), 0);
}
