// The filters' Evaluation and Accuracy: Auto stays exact (bit for bit) on the bundled bunny, switches to the
// multi-resolution evaluation on a dense cloud, says which ran in the field data, and a forced multi-resolution run
// on a real scan stays within the accuracy targets of the exact one.
#include "FilterTestUtilities.h"

#include "vtkGLSContinuousFeatures.h"
#include "vtkGLSScaleSpace.h"

#include "vtkAbstractArray.h"
#include "vtkVariant.h"

#include "gls/Evaluation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace glstest;

namespace
{

vtkPolyData* out(vtkAlgorithm* f)
{
  return vtkPolyData::SafeDownCast(f->GetOutputDataObject(0));
}

std::string evaluationOf(vtkPolyData* output)
{
  vtkAbstractArray* a = output->GetFieldData()->GetAbstractArray("GLSEvaluation");
  return a && a->GetNumberOfTuples() == 1 ? a->GetVariantValue(0).ToString() : std::string();
}

double p99(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v.empty() ? NAN : v[v.size() * 99 / 100];
}

} // namespace

TEST(Evaluation, AutoIsExactBitForBitOnTheBunny)
{
  auto bunny = bunnyMeshWithNormals();
  vtkNew<vtkGLSScaleSpace> automatic, exact;
  automatic->SetInputData(bunny);
  exact->SetInputData(bunny);
  exact->SetEvaluationToExact();
  automatic->Update();
  exact->Update();
  EXPECT_EQ(automatic->GetEvaluation(), vtkGLSScaleSpace::EVALUATION_AUTO); // the default
  EXPECT_EQ(evaluationOf(out(automatic)), "Exact");
  EXPECT_EQ(evaluationOf(out(exact)), "Exact");
  EXPECT_EQ(out(automatic)->GetFieldData()->GetArray("GLSAccuracy"), nullptr);
  for (const char* name : { "GLSTau", "GLSKappa", "GLSFitness", "GLSdTau", "GLSdEta", "GLSdKappa" })
  {
    EXPECT_TRUE(identical(pointArray(out(automatic), name), pointArray(out(exact), name))) << name;
  }
}

TEST(Evaluation, AutoSwitchesToCellsAboveFiveThousandNeighboursAndSpheresStayExact)
{
  // 200,000 points on the unit sphere; the largest scale (0.1 of the diagonal, 0.35) holds about 6,000 of them.
  const Cloud c = sphere(200000, 1.0);
  auto input = makePolyData(c);
  vtkNew<vtkGLSScaleSpace> f;
  f->SetInputData(input);
  f->SetMinScale(0.02);
  f->SetMaxScale(0.1);
  f->SetNumberOfScales(6);
  f->Update();
  ASSERT_EQ(evaluationOf(out(f)), "Multiresolution");
  EXPECT_STREQ(f->GetLastEvaluationUsed(), "Multiresolution");
  EXPECT_EQ(fieldArray(out(f), "GLSAccuracy"), std::vector<double>{ gls::kDefaultAccuracy });
  const std::vector<double> kappa = pointArray(out(f), "GLSKappa");
  ASSERT_EQ(kappa.size(), c.size() * 6);
  for (double k : kappa)
  {
    ASSERT_NEAR(k, 1.0, 1e-12);
  }
  // A sparser sphere at the same relative scales stays exact.
  vtkNew<vtkGLSScaleSpace> sparse;
  sparse->SetInputData(makePolyData(sphere(20000, 1.0)));
  sparse->SetMinScale(0.02);
  sparse->SetMaxScale(0.1);
  sparse->SetNumberOfScales(6);
  sparse->Update();
  EXPECT_EQ(evaluationOf(out(sparse)), "Exact");
}

TEST(Evaluation, MultiresolutionOnANoisyScanStaysWithinTheTargetsOfExact)
{
  // The bunny scan's 35k vertices (a real range scan, with its noise) and their mesh normals, the default scales,
  // every point: forced multi-resolution against exact, features with one absolute sigma so that only the
  // evaluation differs.
  auto bunny = bunnyMeshWithNormals();
  vtkNew<vtkGLSContinuousFeatures> exact, cells;
  for (vtkGLSContinuousFeatures* f : { exact.Get(), cells.Get() })
  {
    f->SetInputData(bunny);
    f->SetSigmaModeToAbsolute();
    f->SetSigma(0.05);
  }
  exact->SetEvaluationToExact();
  cells->SetEvaluationToMultiresolution();
  exact->Update();
  cells->Update();
  ASSERT_EQ(evaluationOf(out(cells)), "Multiresolution");
  const std::vector<double> a = pointArray(out(exact), "GLSFeature");
  const std::vector<double> b = pointArray(out(cells), "GLSFeature");
  ASSERT_EQ(a.size(), b.size());
  std::vector<double> d;
  double largest = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    if (std::isfinite(a[i]) && std::isfinite(b[i]))
    {
      d.push_back(std::abs(a[i] - b[i]));
      largest = std::max(largest, d.back());
    }
  }
  ASSERT_GT(d.size(), a.size() * 9 / 10);
  EXPECT_LT(p99(d), 0.02);
  EXPECT_GT(largest, 0.0); // cells were taken whole: the evaluation is not the exact one
}
