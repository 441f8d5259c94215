// The same answer wherever the data sits: the normals, the features and the per-point summaries of a cloud and of the
// same cloud moved, exact and multi-resolution. Every filter computes on the coordinates from the low corner of the
// cloud's bounds (vtkGLSCloud::Anchor) and the pyramid's lattice starts there: a move whose coordinates are exact
// (survey coordinates on a grid, shifted to UTM) gives the same numbers bit for bit; any other, the same to the
// rounding of the moved coordinates.
#include "FilterTestUtilities.h"

#include "vtkGLSContinuousFeatures.h"
#include "vtkGLSNormalEstimation.h"
#include "vtkGLSScaleFilterBase.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace glstest;

namespace
{

const char* const kCompared[] = { "Normals", "GLSFeature", "GLSStableScale", "GLSStableKappa", "GLSStableTau",
  "GLSMaxVariation", "GLSAnisotropy", "GLSStableShapeIndex" };

/// Every other vertex of the bundled bunny, moved by `shift` (and first rounded to a grid of 2^-20 when `onGrid`: a
/// survey's integers times its scale).
std::vector<double> bunny(const double shift[3], bool onGrid)
{
  const vtkSmartPointer<vtkPolyData> b = bunnyCloud();
  std::vector<double> xyz;
  for (vtkIdType i = 0; i < b->GetNumberOfPoints(); i += 2)
  {
    double p[3];
    b->GetPoint(i, p);
    for (int a = 0; a < 3; ++a)
    {
      const double v = onGrid ? std::ldexp(std::round(std::ldexp(p[a], 20)), -20) : p[a];
      xyz.push_back(v + shift[a]);
    }
  }
  return xyz;
}

/// The normals (estimated) and the fused pass's arrays of a cloud.
vtkSmartPointer<vtkPolyData> analyse(const std::vector<double>& xyz, int evaluation)
{
  vtkNew<vtkGLSNormalEstimation> normals;
  normals->SetInputData(makePolyData(xyz, {}));
  vtkNew<vtkGLSContinuousFeatures> features;
  features->SetInputConnection(normals->GetOutputPort());
  features->SetNumberOfScales(6);
  features->SetMinScale(0.015); // every other vertex: 0.008 of the diagonal holds 4 neighbours, too few to fit
  features->SetScaleSummary(true);
  features->SetDirectionSummary(true);
  features->SetEvaluation(evaluation);
  features->Update();
  return features->GetPolyDataOutput();
}

/// The largest difference between the arrays of two runs (NaN where one is NaN and the other not).
double largestDifference(vtkPolyData* a, vtkPolyData* b, const char* name)
{
  const std::vector<double> x = pointArray(a, name), y = pointArray(b, name);
  EXPECT_EQ(x.size(), y.size()) << name;
  double largest = 0.0;
  for (std::size_t i = 0; i < x.size() && i < y.size(); ++i)
  {
    if (std::isnan(x[i]) != std::isnan(y[i]))
    {
      return std::nan("");
    }
    largest = std::isnan(x[i]) ? largest : std::max(largest, std::abs(x[i] - y[i]));
  }
  return largest;
}

} // namespace

TEST(ShiftInvariance, AnyMoveGivesTheSameResultsToTheRoundingOfTheMovedCoordinates)
{
  // A move of (0.37, 0.21, 0.13): GLSFeature changed by up to 0.020 under the multi-resolution evaluation when the
  // pyramid's lattice was laid from the origin (3e-14 exact); the moved coordinates are rounded by 2^-53 of 0.5.
  const double none[3] = { 0, 0, 0 }, shift[3] = { 0.37, 0.21, 0.13 };
  for (const int evaluation :
    { vtkGLSScaleFilterBase::EVALUATION_EXACT, vtkGLSScaleFilterBase::EVALUATION_MULTIRESOLUTION })
  {
    const auto a = analyse(bunny(none, false), evaluation), b = analyse(bunny(shift, false), evaluation);
    for (const char* name : kCompared)
    {
      const double d = largestDifference(a, b, name);
      std::printf("move (0.37, 0.21, 0.13), evaluation %d: %s within %.3g\n", evaluation, name, d);
      EXPECT_LT(d, 1e-9) << name; // measured at most 6.7e-14 (features) and 4.7e-12 (kappa, 1/length)
    }
  }
}

TEST(ShiftInvariance, AnExactMoveToSurveyCoordinatesGivesTheSameResultsBitForBit)
{
  // The bunny on a grid of 2^-20 (about a micrometre, as a LAS file's integers) moved by (640000, 4200000, 100), as a
  // survey in UTM coordinates: each moved coordinate is exact, so its distance from the low corner is the same
  // double, and every result the same bit for bit. Before the anchor, 3.1e-7 in the features (exact and
  // multi-resolution) and 1.4e-4 in kappa.
  const double none[3] = { 0, 0, 0 }, survey[3] = { 640000.0, 4200000.0, 100.0 };
  for (const int evaluation :
    { vtkGLSScaleFilterBase::EVALUATION_EXACT, vtkGLSScaleFilterBase::EVALUATION_MULTIRESOLUTION })
  {
    const auto a = analyse(bunny(none, true), evaluation), b = analyse(bunny(survey, true), evaluation);
    for (const char* name : kCompared)
    {
      EXPECT_TRUE(identical(pointArray(a, name), pointArray(b, name))) << name << ", evaluation " << evaluation;
    }
    EXPECT_EQ(fieldArray(a, "GLSScales"), fieldArray(b, "GLSScales"));
  }
}
