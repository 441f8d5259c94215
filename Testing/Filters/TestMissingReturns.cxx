// Organized scans (a depth camera's 640 x 480 PCD, a terrestrial scan's grid) hold rows of NaN for their missing
// returns, and some writers put infinities there: every filter leaves those points out of every neighbourhood and of
// the bounds, counts them in the field data GLSNonFinitePoints, writes NaN at their rows, and gives every other row
// what the same cloud without those rows gives, bit for bit.
#include "FilterTestUtilities.h"

#include "vtkGLSAdaptiveBandwidth.h"
#include "vtkGLSContinuousFeatures.h"
#include "vtkGLSGeometricVariation.h"
#include "vtkGLSMultiScaleDissimilarity.h"
#include "vtkGLSNormalEstimation.h"
#include "vtkGLSPrincipalDirections.h"
#include "vtkGLSProjection.h"
#include "vtkGLSScaleProfiles.h"
#include "vtkGLSScaleSpace.h"

#include "vtkTable.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

using namespace glstest;

namespace
{

/// Every third vertex of the bundled bunny laid out as an organized scan: a row of NaN (a missing return) after
/// every 4th point, and two rows with one infinite coordinate; and the same cloud without those rows. `dense[k]`
/// is the row of organized point k in the dense cloud (-1 for the left-out rows).
struct OrganizedScan
{
  std::vector<double> organized, dense;
  std::vector<long long> denseOf;
  long long gaps = 0;
};

OrganizedScan organizedBunny()
{
  const vtkSmartPointer<vtkPolyData> bunny = bunnyCloud();
  OrganizedScan s;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (vtkIdType i = 0; i < bunny->GetNumberOfPoints(); i += 3)
  {
    double p[3];
    bunny->GetPoint(i, p);
    s.organized.insert(s.organized.end(), p, p + 3);
    s.dense.insert(s.dense.end(), p, p + 3);
    s.denseOf.push_back(static_cast<long long>(s.dense.size() / 3 - 1));
    if (s.denseOf.size() % 5 == 4)
    {
      const std::size_t k = s.denseOf.size();
      const double gap[3] = { nan, nan, nan };
      const double far[3] = { p[0], k % 2 ? inf : -inf, p[2] }; // one infinite coordinate
      const double* row = k == 9 || k == 5004 ? far : gap;
      s.organized.insert(s.organized.end(), row, row + 3);
      s.denseOf.push_back(-1);
      ++s.gaps;
    }
  }
  return s;
}

/// The organized cloud's rows of a dense cloud's array: the dense values at the kept rows, NaN at the others.
std::vector<double> organizedRows(const std::vector<double>& dense, int width, const OrganizedScan& s)
{
  std::vector<double> out;
  for (long long d : s.denseOf)
  {
    for (int c = 0; c < width; ++c)
    {
      out.push_back(d < 0 ? std::numeric_limits<double>::quiet_NaN() : dense[static_cast<std::size_t>(d) * width + c]);
    }
  }
  return out;
}

/// The normals of the dense cloud (the default estimation) and the organized cloud's (NaN at the left-out rows).
struct Normals
{
  vtkSmartPointer<vtkPolyData> dense, organized;
};

Normals withNormals(const OrganizedScan& s)
{
  vtkNew<vtkGLSNormalEstimation> estimate;
  estimate->SetInputData(makePolyData(s.dense, {}));
  estimate->Update();
  const std::vector<double> normals = values(estimate->GetOutput()->GetPointData()->GetNormals());
  return { makePolyData(s.dense, normals), makePolyData(s.organized, organizedRows(normals, 3, s)) };
}

/// Runs a filter made by `make` on `input`; its output (a deep copy) and the warnings it gave.
struct FilterRun
{
  vtkSmartPointer<vtkDataObject> output;
  std::string warnings;
};

FilterRun run(const std::function<vtkSmartPointer<vtkAlgorithm>()>& make, vtkPolyData* input)
{
  vtkSmartPointer<vtkAlgorithm> f = make();
  f->SetInputDataObject(input);
  auto warnings = catchWarnings(f);
  auto errors = catchErrors(f);
  f->Update();
  EXPECT_EQ(errors->Count, 0) << errors->Message;
  FilterRun r;
  r.output.TakeReference(f->GetOutputDataObject(0)->NewInstance());
  r.output->DeepCopy(f->GetOutputDataObject(0));
  r.warnings = warnings->Message;
  return r;
}

template <typename Filter>
std::function<vtkSmartPointer<vtkAlgorithm>()> filter(const std::function<void(Filter*)>& set)
{
  return [set]() {
    auto f = vtkSmartPointer<Filter>::New();
    f->SetNumberOfScales(6);
    set(f);
    return f;
  };
}

/// Every point array of `organized` (an organized run) against `dense` (the dense run): NaN at the left-out rows of a
/// floating-point array, every kept row bit for bit; the count in the field data and the warning.
void expectLeftOut(const FilterRun& organizedRun, const FilterRun& denseRun, const OrganizedScan& s, const char* what)
{
  SCOPED_TRACE(what);
  auto* organized = vtkPolyData::SafeDownCast(organizedRun.output);
  auto* dense = vtkPolyData::SafeDownCast(denseRun.output);
  ASSERT_NE(organized, nullptr);
  const std::vector<double> count = fieldArray(organized, "GLSNonFinitePoints");
  ASSERT_EQ(count.size(), 1u);
  EXPECT_EQ(count[0], static_cast<double>(s.gaps));
  EXPECT_TRUE(fieldArray(dense, "GLSNonFinitePoints").empty());
  EXPECT_NE(organizedRun.warnings.find(std::to_string(s.gaps) + " of the"), std::string::npos) << organizedRun.warnings;
  int compared = 0;
  vtkPointData* pd = dense->GetPointData();
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* d = pd->GetArray(a);
    vtkDataArray* o = organized->GetPointData()->GetArray(d->GetName());
    ASSERT_NE(o, nullptr) << d->GetName();
    const int width = d->GetNumberOfComponents();
    const std::vector<double> expected = organizedRows(values(d), width, s);
    const std::vector<double> got = values(o);
    ASSERT_EQ(got.size(), expected.size()) << d->GetName();
    const bool floating = d->GetDataType() == VTK_DOUBLE || d->GetDataType() == VTK_FLOAT;
    for (std::size_t k = 0; k < s.denseOf.size(); ++k)
    {
      for (int c = 0; c < width; ++c)
      {
        const double e = expected[k * width + c], v = got[k * width + c];
        if (s.denseOf[k] >= 0)
        {
          ASSERT_TRUE(e == v || (std::isnan(e) && std::isnan(v))) << d->GetName() << " row " << k << ": " << v
                                                                   << " instead of " << e;
        }
        else if (floating)
        {
          ASSERT_TRUE(std::isnan(v)) << d->GetName() << " at left-out row " << k << ": " << v;
        }
      }
    }
    ++compared;
  }
  EXPECT_GT(compared, 1);
}

} // namespace

TEST(MissingReturns, TheNormalEstimationLeavesThemOut)
{
  const OrganizedScan s = organizedBunny();
  ASSERT_GT(s.gaps, 2000);
  const auto make = []() { return vtkSmartPointer<vtkGLSNormalEstimation>::New(); };
  expectLeftOut(run(make, makePolyData(s.organized, {})), run(make, makePolyData(s.dense, {})), s, "normals");
}

TEST(MissingReturns, EveryScaleFilterLeavesThemOut)
{
  const OrganizedScan s = organizedBunny();
  const Normals n = withNormals(s);
  const std::vector<std::pair<const char*, std::function<vtkSmartPointer<vtkAlgorithm>()>>> filters = {
    { "scale space", filter<vtkGLSScaleSpace>([](vtkGLSScaleSpace*) {}) },
    { "variation", filter<vtkGLSGeometricVariation>([](vtkGLSGeometricVariation*) {}) },
    { "features, summaries and directions (multi-resolution)",
      filter<vtkGLSContinuousFeatures>([](vtkGLSContinuousFeatures* f) {
        f->SetScaleSummary(true);
        f->SetDirectionSummary(true);
        f->SetEvaluationToMultiresolution();
      }) },
    { "principal directions", filter<vtkGLSPrincipalDirections>([](vtkGLSPrincipalDirections*) {}) },
    { "bandwidth", filter<vtkGLSAdaptiveBandwidth>([](vtkGLSAdaptiveBandwidth*) {}) },
  };
  for (const auto& f : filters)
  {
    expectLeftOut(run(f.second, n.organized), run(f.second, n.dense), s, f.first);
  }
  // The dissimilarity to one point: its id in each cloud.
  const long long query = 100;
  long long organizedQuery = 0;
  while (s.denseOf[static_cast<std::size_t>(organizedQuery)] != query)
  {
    ++organizedQuery;
  }
  const auto dissimilarity = [](long long id) {
    return filter<vtkGLSMultiScaleDissimilarity>([id](vtkGLSMultiScaleDissimilarity* f) { f->SetQueryPointId(id); });
  };
  expectLeftOut(run(dissimilarity(organizedQuery), n.organized), run(dissimilarity(query), n.dense), s,
    "dissimilarity");
}

TEST(MissingReturns, TheProjectionLeavesThemInPlace)
{
  // The projection moves each kept point as in the dense cloud; a left-out row keeps its coordinates (NaN or
  // infinite) and gets NaN results.
  const OrganizedScan s = organizedBunny();
  const Normals n = withNormals(s);
  const auto make = []() {
    auto f = vtkSmartPointer<vtkGLSProjection>::New();
    f->SetScaleModeToFixedScale();
    f->SetScale(0.01);
    return f;
  };
  const FilterRun organized = run(make, n.organized), dense = run(make, n.dense);
  expectLeftOut(organized, dense, s, "projection");
  auto* o = vtkPolyData::SafeDownCast(organized.output);
  auto* d = vtkPolyData::SafeDownCast(dense.output);
  for (std::size_t k = 0; k < s.denseOf.size(); ++k)
  {
    double p[3], q[3];
    o->GetPoint(static_cast<vtkIdType>(k), p);
    if (s.denseOf[k] < 0)
    {
      for (int a = 0; a < 3; ++a)
      {
        const double input = s.organized[3 * k + a];
        ASSERT_TRUE(p[a] == input || (std::isnan(p[a]) && std::isnan(input))) << k;
      }
      continue;
    }
    d->GetPoint(static_cast<vtkIdType>(s.denseOf[k]), q);
    ASSERT_TRUE(p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) << k;
  }
}

TEST(MissingReturns, ScaleProfilesOfKeptPointsAreTheDenseClouds)
{
  const OrganizedScan s = organizedBunny();
  const Normals n = withNormals(s);
  std::vector<vtkIdType> organizedIds, denseIds;
  for (std::size_t k = 0; k < s.denseOf.size() && organizedIds.size() < 3; k += 997)
  {
    if (s.denseOf[k] >= 0)
    {
      organizedIds.push_back(static_cast<vtkIdType>(k));
      denseIds.push_back(static_cast<vtkIdType>(s.denseOf[k]));
    }
  }
  const auto profiles = [](const std::vector<vtkIdType>& ids) {
    return filter<vtkGLSScaleProfiles>([ids](vtkGLSScaleProfiles* f) {
      for (vtkIdType id : ids)
      {
        f->AddPointId(id);
      }
    });
  };
  const FilterRun o = run(profiles(organizedIds), n.organized), d = run(profiles(denseIds), n.dense);
  auto* ot = vtkTable::SafeDownCast(o.output);
  auto* dt = vtkTable::SafeDownCast(d.output);
  ASSERT_NE(ot, nullptr);
  ASSERT_EQ(ot->GetNumberOfColumns(), dt->GetNumberOfColumns());
  for (vtkIdType c = 0; c < dt->GetNumberOfColumns(); ++c)
  {
    std::string name = dt->GetColumnName(c);
    for (std::size_t k = 0; k < denseIds.size(); ++k)
    {
      const std::string from = "(" + std::to_string(denseIds[k]) + ")", to = "(" + std::to_string(organizedIds[k]) + ")";
      const auto at = name.find(from);
      if (at != std::string::npos)
      {
        name.replace(at, from.size(), to);
      }
    }
    vtkDataArray* oc = vtkArrayDownCast<vtkDataArray>(ot->GetColumnByName(name.c_str()));
    ASSERT_NE(oc, nullptr) << name;
    EXPECT_TRUE(identical(values(oc), values(vtkArrayDownCast<vtkDataArray>(dt->GetColumn(c))))) << name;
  }
}
