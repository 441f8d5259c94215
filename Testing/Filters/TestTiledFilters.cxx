// Every filter that takes scales, run with a MemoryBudget too small for its engine: it cuts the cloud into spatial
// tiles (field data GLSTiles) and writes the arrays of the untiled run, bit for bit; a budget that no tiling meets is
// refused with an error naming MemoryBudget, and the output is empty.
#include "FilterTestUtilities.h"

#include "vtkGLSAdaptiveBandwidth.h"
#include "vtkGLSContinuousFeatures.h"
#include "vtkGLSGeometricVariation.h"
#include "vtkGLSMultiScaleDissimilarity.h"
#include "vtkGLSPrincipalDirections.h"
#include "vtkGLSScaleSpace.h"

#include "vtkDataArray.h"
#include "vtkPoints.h"
#include "vtkFieldData.h"
#include "vtkPointData.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <string>

using namespace glstest;

namespace
{

using MakeFilter = std::function<vtkSmartPointer<vtkGLSScaleFilterBase>()>;

vtkPolyData* out(vtkAlgorithm* f)
{
  return vtkPolyData::SafeDownCast(f->GetOutputDataObject(0));
}

long long tilesOf(vtkPolyData* output)
{
  vtkDataArray* a = output->GetFieldData()->GetArray("GLSTiles");
  return a ? static_cast<long long>(a->GetTuple1(0)) : 1;
}

bool compactNormalsOf(vtkPolyData* output)
{
  vtkDataArray* a = output->GetFieldData()->GetArray("GLSCompactNormals");
  return a && a->GetTuple1(0) == 1.0;
}

/// Every point array of `output` holds the bits of `expected`'s.
void expectTheSameArrays(vtkPolyData* output, vtkPolyData* expected)
{
  ASSERT_EQ(output->GetPointData()->GetNumberOfArrays(), expected->GetPointData()->GetNumberOfArrays());
  for (int a = 0; a < expected->GetPointData()->GetNumberOfArrays(); ++a)
  {
    const char* array = expected->GetPointData()->GetArrayName(a);
    EXPECT_TRUE(identical(pointArray(output, array), pointArray(expected, array))) << array;
  }
}

/// The filters that tile, each as a user would set it up (the features with their scale summary and relative sigma,
/// whose sample of nu runs through the tiles too; the principal curvatures' reductions, alone and in the features'
/// pass as the main job runs it).
std::vector<std::pair<std::string, MakeFilter>> tilingFilters()
{
  return {
    { "ScaleSpace", [] { return vtkSmartPointer<vtkGLSScaleSpace>::New(); } },
    { "GeometricVariation", [] { return vtkSmartPointer<vtkGLSGeometricVariation>::New(); } },
    { "ContinuousFeatures",
      [] {
        auto f = vtkSmartPointer<vtkGLSContinuousFeatures>::New();
        f->SetScaleSummary(true);
        return f;
      } },
    { "MultiScaleDissimilarity",
      [] {
        auto f = vtkSmartPointer<vtkGLSMultiScaleDissimilarity>::New();
        f->SetQueryPointId(1234);
        return f;
      } },
    { "AdaptiveBandwidth", [] { return vtkSmartPointer<vtkGLSAdaptiveBandwidth>::New(); } },
    { "PrincipalDirections", [] { return vtkSmartPointer<vtkGLSPrincipalDirections>::New(); } },
    { "ContinuousFeaturesWithDirections",
      [] {
        auto f = vtkSmartPointer<vtkGLSContinuousFeatures>::New();
        f->SetScaleSummary(true);
        f->SetDirectionSummary(true);
        return f;
      } },
  };
}

/// Runs a fresh filter on the input with the budget (MiB); the output (empty when the run failed) and its errors.
vtkSmartPointer<vtkPolyData> runWithBudget(
  const MakeFilter& make, vtkPolyData* input, bool multiresolution, double budget, int* errors = nullptr)
{
  vtkSmartPointer<vtkGLSScaleFilterBase> f = make();
  f->SetInputData(input);
  f->SetNumberOfScales(8);
  f->SetMaxScale(0.03); // a band narrower than the bunny, so that tiles help

  f->SetMemoryBudget(budget);
  if (multiresolution)
  {
    f->SetEvaluationToMultiresolution();
  }
  else
  {
    f->SetEvaluationToExact();
  }
  auto caught = catchErrors(f);
  f->Update();
  if (errors)
  {
    *errors = caught->Count;
  }
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(out(f));
  return copy;
}

} // namespace

TEST(TiledFilters, EveryScaleFilterTiledUnderATightBudgetWritesTheUntiledArraysBitForBit)
{
  const auto bunny = bunnyMeshWithNormals();
  for (const auto& [name, make] : tilingFilters())
  {
    for (bool multiresolution : { false, true })
    {
      SCOPED_TRACE(name + (multiresolution ? ", multi-resolution" : ", exact"));
      const auto whole = runWithBudget(make, bunny, multiresolution, 0.0);
      ASSERT_GT(whole->GetNumberOfPoints(), 0);
      ASSERT_EQ(whole->GetFieldData()->GetArray("GLSTiles"), nullptr);
      // About the tightest budget the filter still meets (bisected): by then its engine is cut into several tiles.
      vtkSmartPointer<vtkPolyData> tiled;
      double met = 64.0, refused = 0.01;
      for (int step = 0; step < 10; ++step)
      {
        const double budget = std::sqrt(met * refused);
        int errors = 0;
        const auto output = runWithBudget(make, bunny, multiresolution, budget, &errors);
        if (errors > 0)
        {
          EXPECT_EQ(output->GetNumberOfPoints(), 0);
          refused = budget;
        }
        else
        {
          met = budget;
          tiled = output;
        }
      }
      ASSERT_TRUE(tiled);
      EXPECT_GE(tilesOf(tiled), 4);
      // The bunny's normals are vtkPolyDataNormals' float32: a pyramid's tiles keep them compact (its coordinates,
      // doubles read from the OBJ file, not).
      EXPECT_EQ(compactNormalsOf(tiled), multiresolution);
      vtkPointData* expected = whole->GetPointData();
      ASSERT_EQ(tiled->GetPointData()->GetNumberOfArrays(), expected->GetNumberOfArrays());
      for (int a = 0; a < expected->GetNumberOfArrays(); ++a)
      {
        const char* array = expected->GetArrayName(a);
        EXPECT_TRUE(identical(pointArray(tiled, array), pointArray(whole, array))) << array;
      }
      for (int a = 0; a < whole->GetFieldData()->GetNumberOfArrays(); ++a)
      {
        const char* array = whole->GetFieldData()->GetArrayName(a);
        if (whole->GetFieldData()->GetArray(array))
        {
          EXPECT_TRUE(identical(fieldArray(tiled, array), fieldArray(whole, array))) << array;
        }
      }
    }
  }
}

TEST(TiledFilters, ABudgetBelowTheEnginesNeedKeepsFloatNormalsCompactWithTheSameArrays)
{
  // The bunny in float32 (its normals are vtkPolyDataNormals', float32): under a budget the multi-resolution engine
  // with unit normals in doubles does not meet, the filter keeps them as given (field data GLSCompactNormals) before
  // it cuts tiles, and writes the arrays of the unconstrained run bit for bit.
  const auto bunny = vtkSmartPointer<vtkPolyData>::New();
  bunny->DeepCopy(bunnyMeshWithNormals());
  vtkNew<vtkPoints> single;
  single->SetDataTypeToFloat();
  single->DeepCopy(bunny->GetPoints());
  bunny->SetPoints(single);
  ASSERT_EQ(bunny->GetPointData()->GetNormals()->GetDataType(), VTK_FLOAT);
  ASSERT_EQ(bunny->GetPoints()->GetDataType(), VTK_FLOAT);
  for (const auto& [name, make] : tilingFilters())
  {
    if (name != "ContinuousFeatures" && name != "ScaleSpace")
    {
      continue;
    }
    SCOPED_TRACE(name);
    const auto whole = runWithBudget(make, bunny, true, 0.0);
    ASSERT_GT(whole->GetNumberOfPoints(), 0);
    EXPECT_FALSE(compactNormalsOf(whole));
    // The smallest budget of the engine as it is (bisected to 0.1%): just below it the normals are compact.
    const auto asItIs = [&](double budget) {
      int errors = 0;
      const auto output = runWithBudget(make, bunny, true, budget, &errors);
      return errors == 0 && !compactNormalsOf(output) && tilesOf(output) == 1;
    };
    double met = 64.0, missed = 1.0;
    ASSERT_TRUE(asItIs(met));
    ASSERT_FALSE(asItIs(missed));
    while (met > 1.001 * missed)
    {
      const double budget = std::sqrt(met * missed);
      (asItIs(budget) ? met : missed) = budget;
    }
    int errors = 0;
    const auto compact = runWithBudget(make, bunny, true, missed, &errors);
    ASSERT_EQ(errors, 0);
    EXPECT_TRUE(compactNormalsOf(compact));
    EXPECT_EQ(tilesOf(compact), 1);
    expectTheSameArrays(compact, whole);
    // Lower still, the normals stay compact (in tiles where the fit is cut: EveryScaleFilterTiled...) until the
    // budget is refused.
    int refused = 0;
    for (double share = 0.95; share > 0.2; share -= 0.05)
    {
      const auto lower = runWithBudget(make, bunny, true, share * missed, &errors);
      if (errors == 0)
      {
        EXPECT_EQ(refused, 0) << share;
        EXPECT_TRUE(compactNormalsOf(lower));
        expectTheSameArrays(lower, whole);
      }
      refused += errors > 0 ? 1 : 0;
    }
    EXPECT_GT(refused, 0);
  }
}

TEST(TiledFilters, ABudgetNoTilingMeetsIsRefusedNamingTheBudget)
{
  // The largest scale spans the whole bunny: every tile's band holds the whole cloud, so cutting cannot help.
  const auto bunny = bunnyMeshWithNormals();
  vtkNew<vtkGLSGeometricVariation> f;
  f->SetInputData(bunny);
  f->SetMinScale(0.5);
  f->SetMaxScale(1.0);
  f->SetNumberOfScales(4);
  f->SetMemoryBudget(2.0); // the outputs fit, the engine does not
  auto errors = catchErrors(f);
  f->Update();
  EXPECT_GE(errors->Count, 1);
  EXPECT_NE(errors->Message.find("MemoryBudget"), std::string::npos) << errors->Message;
  EXPECT_NE(errors->Message.find("spatial tiles"), std::string::npos) << errors->Message;
  EXPECT_EQ(out(f)->GetNumberOfPoints(), 0);
}
