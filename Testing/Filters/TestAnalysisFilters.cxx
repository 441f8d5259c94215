// vtkGLSGeometricVariation, vtkGLSContinuousFeatures, vtkGLSMultiScaleDissimilarity: analytic sphere, the bunny
// scan, agreement between the fused path and the path through stored arrays, formulas recomputed from the stored
// descriptors, bad input.
#include "FilterTestUtilities.h"

#include "vtkGLSContinuousFeatures.h"
#include "vtkGLSGeometricVariation.h"
#include "vtkGLSMultiScaleDissimilarity.h"
#include "vtkGLSNormalEstimation.h"
#include "vtkGLSScaleSpace.h"

#include "vtkIdTypeArray.h"
#include "vtkPointData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace glstest;

namespace
{

/// The bunny with estimated normals, computed once.
vtkPolyData* bunnyWithNormals()
{
  static vtkSmartPointer<vtkPolyData> cached;
  if (!cached)
  {
    vtkNew<vtkGLSNormalEstimation> n;
    n->SetInputData(bunnyCloud());
    n->Update();
    cached = vtkSmartPointer<vtkPolyData>::New();
    cached->ShallowCopy(n->GetOutput());
  }
  return cached;
}

/// The bunny scale space (default scales: 20 quadratic, 0.8% to 8% of the diagonal), computed once.
vtkPolyData* bunnyScaleSpace()
{
  static vtkSmartPointer<vtkPolyData> cached;
  if (!cached)
  {
    vtkNew<vtkGLSScaleSpace> s;
    s->SetInputData(bunnyWithNormals());
    s->Update();
    cached = vtkSmartPointer<vtkPolyData>::New();
    cached->ShallowCopy(s->GetOutput());
  }
  return cached;
}

template <typename Filter>
vtkSmartPointer<vtkPolyData> run(Filter* f, vtkPolyData* input)
{
  f->SetInputData(input);
  f->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(f->GetOutput());
  return out;
}

bool sameOrBothNaN(double a, double b)
{
  return identical({ a }, { b });
}

} // namespace

TEST(GeometricVariationFilter, SphereHasZeroVariationAndNoPertinentScale)
{
  const Cloud c = sphere(3000, 1.0);
  vtkNew<vtkGLSGeometricVariation> f;
  f->SetScaleUnitsToAbsolute();
  f->SetMinScale(0.2);
  f->SetMaxScale(1.2);
  f->SetNumberOfScales(8);
  auto out = run(f.Get(), makePolyData(c));
  const auto nu = pointArray(out, "GLSGeometricVariation");
  ASSERT_EQ(nu.size(), 3000u * 8);
  for (double v : nu)
  {
    ASSERT_NEAR(v, 0.0, 1e-12);
  }
  const auto count = pointArray(out, "GLSPertinentScaleCount");
  EXPECT_EQ(*std::max_element(count.begin(), count.end()), 0.0);
  const auto pertinent = pointArray(out, "GLSPertinentScales");
  EXPECT_TRUE(std::all_of(pertinent.begin(), pertinent.end(), [](double v) { return std::isnan(v); }));
}

TEST(GeometricVariationFilter, BunnyVariationFromStoredArraysEqualsFusedAndFollowsEquation5)
{
  vtkNew<vtkGLSGeometricVariation> fused;
  auto a = run(fused.Get(), bunnyWithNormals());
  vtkNew<vtkGLSGeometricVariation> stored;
  auto b = run(stored.Get(), bunnyScaleSpace());
  const auto nuA = pointArray(a, "GLSGeometricVariation");
  const auto nuB = pointArray(b, "GLSGeometricVariation");
  ASSERT_EQ(nuA.size(), nuB.size());
  for (std::size_t i = 0; i < nuA.size(); ++i)
  {
    ASSERT_TRUE(sameOrBothNaN(nuA[i], nuB[i])) << i;
  }
  // Recompute nu from the stored derivatives with other weights.
  vtkNew<vtkGLSGeometricVariation> weighted;
  weighted->SetWTau(2.0);
  weighted->SetWEta(0.5);
  weighted->SetWKappa(3.0);
  auto w = run(weighted.Get(), bunnyScaleSpace());
  const auto nuW = pointArray(w, "GLSGeometricVariation");
  const auto scales = fieldArray(bunnyScaleSpace(), "GLSScales");
  const auto dtau = pointArray(bunnyScaleSpace(), "GLSdTau");
  const auto deta = pointArray(bunnyScaleSpace(), "GLSdEta");
  const auto dkappa = pointArray(bunnyScaleSpace(), "GLSdKappa");
  const std::size_t S = scales.size();
  std::size_t finite = 0;
  for (std::size_t i = 0; i < nuW.size() / S; i += 7)
  {
    for (std::size_t k = 0; k < S; ++k)
    {
      const double t = scales[k];
      const double* e = &deta[3 * (i * S + k)];
      const double expected = 2.0 * dtau[i * S + k] * dtau[i * S + k] +
        0.5 * t * t * (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]) +
        3.0 * t * t * t * t * dkappa[i * S + k] * dkappa[i * S + k];
      if (std::isnan(expected))
      {
        ASSERT_TRUE(std::isnan(nuW[i * S + k]));
        continue;
      }
      ++finite;
      ASSERT_NEAR(nuW[i * S + k], expected, 1e-13 * (1 + expected));
    }
  }
  EXPECT_GT(finite, 90000u);

  // Every reported pertinent scale is a strict local minimum of the output nu.
  const auto count = pointArray(a, "GLSPertinentScaleCount");
  const auto pertinent = pointArray(a, "GLSPertinentScales");
  std::size_t reported = 0;
  for (std::size_t i = 0; i < count.size(); ++i)
  {
    for (int j = 0; j < static_cast<int>(count[i]); ++j)
    {
      const auto it = std::find(scales.begin(), scales.end(), pertinent[3 * i + j]);
      ASSERT_NE(it, scales.end());
      const std::size_t k = static_cast<std::size_t>(it - scales.begin());
      ASSERT_TRUE(k > 0 && k + 1 < S);
      ASSERT_LT(nuA[i * S + k], nuA[i * S + k - 1]);
      ASSERT_LE(nuA[i * S + k], nuA[i * S + k + 1]);
      ++reported;
    }
  }
  EXPECT_GT(reported, count.size() / 2); // most points of a real scan have a pertinent scale
}

TEST(ContinuousFeaturesFilter, SphereIsZeroAndBunnySpreadsOverTheUnitInterval)
{
  const Cloud c = sphere(3000, 1.0);
  vtkNew<vtkGLSContinuousFeatures> f;
  f->SetNumberOfScales(6);
  f->SetMinScale(0.05);
  f->SetMaxScale(0.4);
  auto s = run(f.Get(), makePolyData(c));
  for (double v : pointArray(s, "GLSFeature"))
  {
    ASSERT_NEAR(v, 0.0, 1e-12);
  }

  vtkNew<vtkGLSContinuousFeatures> fused;
  auto a = run(fused.Get(), bunnyWithNormals());
  const auto fa = pointArray(a, "GLSFeature");
  vtkNew<vtkGLSContinuousFeatures> fromDerivatives;
  auto b = run(fromDerivatives.Get(), bunnyScaleSpace());
  vtkNew<vtkGLSGeometricVariation> variation;
  auto nu = run(variation.Get(), bunnyScaleSpace());
  vtkNew<vtkGLSContinuousFeatures> fromNu;
  auto c2 = run(fromNu.Get(), nu);
  const auto fb = pointArray(b, "GLSFeature");
  const auto fc = pointArray(c2, "GLSFeature");
  ASSERT_EQ(fa.size(), 35947u);
  double lo = 1.0, hi = 0.0;
  for (std::size_t i = 0; i < fa.size(); ++i)
  {
    ASSERT_TRUE(sameOrBothNaN(fa[i], fb[i])) << i;
    ASSERT_TRUE(sameOrBothNaN(fa[i], fc[i])) << i;
    if (!std::isnan(fa[i]))
    {
      ASSERT_GE(fa[i], 0.0);
      ASSERT_LE(fa[i], 1.0);
      lo = std::min(lo, fa[i]);
      hi = std::max(hi, fa[i]);
    }
  }
  EXPECT_LT(lo, 0.05);
  EXPECT_GT(hi, 0.8);

  // Log measure on the stored nu: recompute one point by hand (trapezoid in ln t).
  vtkNew<vtkGLSContinuousFeatures> logf;
  logf->SetFeatureMeasureToLogScale();
  logf->SetSigmaModeToAbsolute();
  logf->SetSigma(0.5);
  auto l = run(logf.Get(), nu);
  const auto scales = fieldArray(nu, "GLSScales");
  const auto nuv = pointArray(nu, "GLSGeometricVariation");
  const std::size_t S = scales.size(), p = 1234;
  double integral = 0, length = 0;
  for (std::size_t k = 0; k + 1 < S; ++k)
  {
    const double h = std::log(scales[k + 1] / scales[k]);
    integral += 0.5 * h * (std::tanh(nuv[p * S + k] / 0.5) + std::tanh(nuv[p * S + k + 1] / 0.5));
    length += h;
  }
  EXPECT_NEAR(pointArray(l, "GLSFeature")[p], integral / length, 1e-14);
}

TEST(ContinuousFeaturesFilter, ScaleSummaryFollowsTheStoredScaleSpaceAndKeepsTheFeature)
{
  vtkNew<vtkGLSContinuousFeatures> plain;
  auto a = run(plain.Get(), bunnyWithNormals());
  vtkNew<vtkGLSContinuousFeatures> summary;
  summary->ScaleSummaryOn();
  auto b = run(summary.Get(), bunnyWithNormals());
  EXPECT_TRUE(identical(pointArray(a, "GLSFeature"), pointArray(b, "GLSFeature")));
  EXPECT_EQ(plain->GetLastSigma(), summary->GetLastSigma());
  // From the stored scale space, the summary is the same bits as the fused pass.
  vtkNew<vtkGLSContinuousFeatures> fromStored;
  fromStored->ScaleSummaryOn();
  auto c = run(fromStored.Get(), bunnyScaleSpace());
  const char* names[] = { "GLSFeature", "GLSPertinentScaleCount", "GLSStableScale", "GLSStableTau", "GLSStableKappa",
    "GLSStablePhi", "GLSMaxVariation", "GLSMaxVariationScale" };
  for (const char* name : names)
  {
    ASSERT_NE(b->GetPointData()->GetArray(name), nullptr) << name;
    EXPECT_TRUE(identical(pointArray(b, name), pointArray(c, name))) << name;
  }
  // The rule (docs/math.md, "Scale summary") recomputed here from nu and the stored descriptors.
  vtkNew<vtkGLSGeometricVariation> variation;
  auto v = run(variation.Get(), bunnyScaleSpace());
  const auto nu = pointArray(v, "GLSGeometricVariation");
  const auto scales = fieldArray(bunnyScaleSpace(), "GLSScales");
  const auto tau = pointArray(bunnyScaleSpace(), "GLSTau");
  const auto kappa = pointArray(bunnyScaleSpace(), "GLSKappa");
  const auto phi = pointArray(bunnyScaleSpace(), "GLSFitness");
  const auto count = pointArray(b, "GLSPertinentScaleCount");
  const auto stable = pointArray(b, "GLSStableScale");
  const auto stableTau = pointArray(b, "GLSStableTau");
  const auto stableKappa = pointArray(b, "GLSStableKappa");
  const auto stablePhi = pointArray(b, "GLSStablePhi");
  const auto maxNu = pointArray(b, "GLSMaxVariation");
  const auto maxNuScale = pointArray(b, "GLSMaxVariationScale");
  const std::size_t S = scales.size();
  const double noise = 1e-12;
  std::size_t withPertinent = 0, undefined = 0;
  for (std::size_t i = 0; i < stable.size(); ++i)
  {
    const double* row = &nu[i * S];
    int minima = 0;
    long lowestMinimum = -1, lowest = -1, highest = -1;
    for (std::size_t k = 0; k < S; ++k)
    {
      if (std::isnan(row[k]))
      {
        continue;
      }
      if (k > 0 && k + 1 < S && row[k] < row[k - 1] - noise && row[k] <= row[k + 1] + noise)
      {
        ++minima;
        lowestMinimum = lowestMinimum < 0 || row[k] < row[lowestMinimum] ? static_cast<long>(k) : lowestMinimum;
      }
      lowest = lowest < 0 || row[k] < row[lowest] - noise ? static_cast<long>(k) : lowest;
      highest = highest < 0 || row[k] > row[highest] ? static_cast<long>(k) : highest;
    }
    ASSERT_EQ(count[i], minima) << i;
    withPertinent += minima > 0 ? 1 : 0;
    const long k = lowestMinimum >= 0 ? lowestMinimum : lowest;
    if (k < 0)
    {
      ++undefined;
      ASSERT_TRUE(std::isnan(stable[i]) && std::isnan(stableTau[i]) && std::isnan(maxNu[i])) << i;
      continue;
    }
    const std::size_t at = i * S + static_cast<std::size_t>(k);
    ASSERT_EQ(stable[i], scales[static_cast<std::size_t>(k)]) << i;
    ASSERT_TRUE(sameOrBothNaN(stableTau[i], tau[at])) << i;
    ASSERT_TRUE(sameOrBothNaN(stableKappa[i], kappa[at])) << i;
    ASSERT_TRUE(sameOrBothNaN(stablePhi[i], phi[at])) << i;
    ASSERT_EQ(maxNu[i], row[highest]) << i;
    ASSERT_EQ(maxNuScale[i], scales[static_cast<std::size_t>(highest)]) << i;
  }
  // The bunny has pertinent scales at most points, and few points without any defined nu.
  EXPECT_GT(withPertinent, stable.size() / 2);
  EXPECT_LT(undefined, stable.size() / 100);
}

TEST(OutputPrecision, SingleWritesFloatsRoundedFromTheDoublesOfADoubleRun)
{
  // Normal estimation: Normals and NormalQuality as floats, each the float nearest the double run's value.
  vtkNew<vtkGLSNormalEstimation> singleNormals;
  singleNormals->SetOutputPrecision(vtkAlgorithm::SINGLE_PRECISION);
  auto sn = run(singleNormals.Get(), bunnyCloud());
  const auto expectNarrowed = [](vtkPolyData* narrow, vtkPolyData* wide, const char* name) {
    vtkDataArray* f = narrow->GetPointData()->GetArray(name);
    vtkDataArray* d = wide->GetPointData()->GetArray(name);
    ASSERT_TRUE(f && d) << name;
    EXPECT_EQ(f->GetDataType(), VTK_FLOAT) << name;
    EXPECT_EQ(d->GetDataType(), VTK_DOUBLE) << name;
    ASSERT_EQ(f->GetNumberOfValues(), d->GetNumberOfValues()) << name;
    std::size_t finite = 0;
    for (vtkIdType k = 0; k < f->GetNumberOfValues(); ++k)
    {
      const float expected = static_cast<float>(d->GetVariantValue(k).ToDouble());
      const float got = static_cast<float>(f->GetVariantValue(k).ToDouble());
      ASSERT_TRUE(identical({ double(got) }, { double(expected) })) << name << " value " << k;
      finite += std::isfinite(got) ? 1 : 0;
    }
    EXPECT_GT(finite, static_cast<std::size_t>(f->GetNumberOfValues()) / 2) << name;
  };
  expectNarrowed(sn, bunnyWithNormals(), "Normals");
  expectNarrowed(sn, bunnyWithNormals(), "NormalQuality");
  EXPECT_EQ(sn->GetPointData()->GetNormals(), sn->GetPointData()->GetArray("Normals"));
  // The fused features and summary, on the same (double) normals.
  vtkNew<vtkGLSContinuousFeatures> wide, narrow;
  wide->ScaleSummaryOn();
  narrow->ScaleSummaryOn();
  narrow->SetOutputPrecision(vtkAlgorithm::SINGLE_PRECISION);
  auto d = run(wide.Get(), bunnyWithNormals());
  auto f = run(narrow.Get(), bunnyWithNormals());
  for (const char* name : { "GLSFeature", "GLSStableScale", "GLSStableTau", "GLSStableKappa", "GLSStablePhi",
         "GLSMaxVariation", "GLSMaxVariationScale" })
  {
    expectNarrowed(f, d, name);
  }
  EXPECT_TRUE(identical(pointArray(f, "GLSPertinentScaleCount"), pointArray(d, "GLSPertinentScaleCount")));
  EXPECT_EQ(f->GetPointData()->GetArray("GLSPertinentScaleCount")->GetDataType(), VTK_INT);
  // Without the summary, GLSFeature alone.
  vtkNew<vtkGLSContinuousFeatures> plain;
  plain->SetOutputPrecision(vtkAlgorithm::SINGLE_PRECISION);
  expectNarrowed(run(plain.Get(), bunnyWithNormals()), d, "GLSFeature");
  // Neither single nor double: refused.
  vtkNew<vtkGLSContinuousFeatures> bad;
  bad->SetOutputPrecision(vtkAlgorithm::DEFAULT_PRECISION);
  const auto errors = catchErrors(bad.Get());
  auto none = run(bad.Get(), bunnyWithNormals());
  EXPECT_EQ(none->GetPointData()->GetArray("GLSFeature"), nullptr);
  EXPECT_NE(errors->Message.find("Invalid OutputPrecision"), std::string::npos) << errors->Message;
}

TEST(DissimilarityFilter, SphereIsUniformAndTheQueryIsSimilarToItself)
{
  const Cloud c = sphere(3000, 1.0);
  vtkNew<vtkGLSMultiScaleDissimilarity> f;
  f->SetQueryPointId(17);
  auto out = run(f.Get(), makePolyData(c));
  const auto d = pointArray(out, "GLSDissimilarity");
  const auto similar = pointArray(out, "GLSSimilar");
  for (std::size_t i = 0; i < d.size(); ++i)
  {
    ASSERT_NEAR(d[i], 0.0, 1e-18);
    ASSERT_EQ(similar[i], 1.0);
  }
  EXPECT_EQ(fieldArray(out, "GLSQueryPointId"), std::vector<double>{ 17.0 });
}

TEST(DissimilarityFilter, BunnyFusedEqualsStoredAndFollowsEquation6)
{
  const vtkIdType query = 4242;
  vtkNew<vtkGLSMultiScaleDissimilarity> fused;
  fused->SetQueryPointId(query);
  fused->SetPriorMinScale(0.02);
  fused->SetPriorMaxScale(0.06);
  auto a = run(fused.Get(), bunnyWithNormals());
  vtkNew<vtkGLSMultiScaleDissimilarity> stored;
  stored->SetQueryPointId(query);
  stored->SetPriorMinScale(0.02);
  stored->SetPriorMaxScale(0.06);
  auto b = run(stored.Get(), bunnyScaleSpace());
  const auto da = pointArray(a, "GLSDissimilarity");
  const auto db = pointArray(b, "GLSDissimilarity");
  ASSERT_EQ(da.size(), 35947u);
  EXPECT_EQ(da[query], 0.0);
  for (std::size_t i = 0; i < da.size(); ++i)
  {
    ASSERT_TRUE(sameOrBothNaN(da[i], db[i])) << i;
  }

  // Recompute Delta(q, p) for a few points from the stored tau, kappa, phi with the box prior.
  vtkPolyData* ss = bunnyScaleSpace();
  const auto scales = fieldArray(ss, "GLSScales");
  const auto tau = pointArray(ss, "GLSTau");
  const auto kappa = pointArray(ss, "GLSKappa");
  const auto phi = pointArray(ss, "GLSFitness");
  double bounds[6];
  ss->GetBounds(bounds);
  const double diag = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
    (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) + (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  const std::size_t S = scales.size();
  std::size_t similar = 0;
  const auto flags = pointArray(a, "GLSSimilar");
  for (std::size_t p = 0; p < da.size(); p += 97)
  {
    double sum = 0, weight = 0;
    for (std::size_t k = 0; k < S; ++k)
    {
      if (scales[k] < 0.02 * diag || scales[k] > 0.06 * diag)
      {
        continue;
      }
      const double t = scales[k];
      const std::size_t q = static_cast<std::size_t>(query) * S + k, o = p * S + k;
      const double d = std::pow(tau[q] / t - tau[o] / t, 2) + std::pow(t * kappa[q] - t * kappa[o], 2) +
        std::pow(phi[q] - phi[o], 2);
      if (!std::isnan(d))
      {
        sum += d;
        weight += 1.0;
      }
    }
    ASSERT_NEAR(da[p], sum / weight, 1e-12 * (1 + sum / weight)) << p;
    ASSERT_EQ(flags[p], da[p] < 0.01 ? 1.0 : 0.0);
    similar += flags[p] > 0 ? 1 : 0;
  }
  EXPECT_GT(similar, 0u);
  EXPECT_LT(similar, da.size() / 97);
}

TEST(DissimilarityFilter, QueryByCoordinatesSnapsToTheNearestPoint)
{
  vtkPolyData* ss = bunnyScaleSpace();
  double p[3];
  ss->GetPoint(1000, p);
  vtkNew<vtkGLSMultiScaleDissimilarity> f;
  f->SetUseQueryPointCoordinates(true);
  f->SetQueryPoint(p[0] + 1e-6, p[1], p[2]);
  f->SetPriorShapeToLogGaussian();
  auto out = run(f.Get(), ss);
  EXPECT_EQ(fieldArray(out, "GLSQueryPointId"), std::vector<double>{ 1000.0 });
  EXPECT_EQ(pointArray(out, "GLSDissimilarity")[1000], 0.0);
}

TEST(DissimilarityFilter, BadQueryAndPriorGiveClearErrors)
{
  const Cloud c = sphere(500, 1.0);
  vtkNew<vtkGLSMultiScaleDissimilarity> f;
  auto errors = catchErrors(f);
  f->SetInputData(makePolyData(c));
  f->SetQueryPointId(500);
  f->Update();
  EXPECT_NE(errors->Message.find("out of range"), std::string::npos) << errors->Message;
  f->SetQueryPointId(-1); // an error, not point 0
  f->Update();
  EXPECT_EQ(errors->Count, 2);
  EXPECT_NE(errors->Message.find("QueryPointId must be a point id"), std::string::npos) << errors->Message;
  EXPECT_EQ(f->GetOutput()->GetPointData()->GetArray("GLSDissimilarity"), nullptr);
  f->SetQueryPointId(0);
  f->SetPriorMinScale(2.0);
  f->SetPriorMaxScale(3.0);
  f->Update();
  EXPECT_NE(errors->Message.find("prior"), std::string::npos) << errors->Message;
  EXPECT_EQ(f->GetOutput()->GetPointData()->GetArray("GLSDissimilarity"), nullptr);
  // A query point by coordinates: far from the cloud (at 1e300, "no input point with finite coordinates" once), or
  // not finite.
  f->SetPriorMinScale(0.0);
  f->SetPriorMaxScale(0.0);
  f->SetUseQueryPointCoordinates(true);
  f->SetQueryPoint(1e300, 0.0, 0.0);
  f->Update();
  EXPECT_EQ(errors->Count, 4);
  EXPECT_NE(errors->Message.find("is 1e+300 from the nearest input point, farther than the input's bounding-box "
                                 "diagonal"), std::string::npos) << errors->Message;
  f->SetQueryPoint(0.0, std::numeric_limits<double>::infinity(), 0.0);
  f->Update();
  EXPECT_EQ(errors->Count, 5);
  EXPECT_NE(errors->Message.find("QueryPoint (0, inf, 0) must be finite"), std::string::npos) << errors->Message;
  // Near the cloud: the nearest point, no error.
  f->SetQueryPoint(0.0, 0.0, 1.1);
  f->Update();
  EXPECT_EQ(errors->Count, 5);
  EXPECT_NE(f->GetOutput()->GetPointData()->GetArray("GLSDissimilarity"), nullptr);
}

TEST(FeaturesFilter, ZeroNegativeOrNonFiniteSigmaIsAnError)
{
  // Sigma is the scale of tanh(nu / Sigma): 0 or a negative value used to be clamped, making every feature 1.
  const Cloud c = sphere(500, 1.0);
  for (double sigma : { 0.0, -0.1, std::numeric_limits<double>::quiet_NaN() })
  {
    vtkNew<vtkGLSContinuousFeatures> f;
    auto errors = catchErrors(f);
    f->SetSigmaModeToAbsolute();
    f->SetSigma(sigma);
    f->SetInputData(makePolyData(c));
    f->Update();
    EXPECT_EQ(errors->Count, 1) << sigma;
    EXPECT_NE(errors->Message.find("Sigma must be a positive"), std::string::npos) << errors->Message;
    EXPECT_EQ(f->GetOutput()->GetPointData()->GetArray("GLSFeature"), nullptr) << sigma;
  }
}

TEST(AnalysisFilters, MissingNormalsAndEmptyInputGiveClearErrors)
{
  const Cloud c = sphere(200, 1.0);
  vtkNew<vtkGLSGeometricVariation> v;
  auto ev = catchErrors(v);
  run(v.Get(), makePolyData(c.points, {}));
  EXPECT_NE(ev->Message.find("no normals"), std::string::npos) << ev->Message;
  vtkNew<vtkGLSContinuousFeatures> f;
  auto ef = catchErrors(f);
  run(f.Get(), makePolyData(std::vector<double>{}, {}));
  EXPECT_NE(ef->Message.find("no points"), std::string::npos) << ef->Message;
  vtkNew<vtkGLSMultiScaleDissimilarity> d;
  auto ed = catchErrors(d);
  d->SetMinScale(-1.0);
  run(d.Get(), makePolyData(c));
  EXPECT_NE(ed->Message.find("MinScale"), std::string::npos) << ed->Message;
}

TEST(AllFilters, PlaneGivesFlatDescriptorsThroughTheWholePipeline)
{
  // A jittered-free grid in z = 0.5: normals +z (towards a point above), kappa 0, tau 0, nu 0, f 0, Delta 0.
  Cloud c = plane(60, 2.0);
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    c.points[3 * i + 2] = 0.5;
  }
  vtkNew<vtkGLSNormalEstimation> normals;
  normals->SetInputData(makePolyData(c.points, {}));
  normals->SetOrientationToTowardsPoint();
  normals->SetOrientationPoint(0, 0, 10);
  vtkNew<vtkGLSScaleSpace> scales;
  scales->SetInputConnection(normals->GetOutputPort());
  scales->SetNumberOfScales(5);
  scales->SetMinScale(0.03);
  scales->SetMaxScale(0.15);
  vtkNew<vtkGLSGeometricVariation> variation;
  variation->SetInputConnection(scales->GetOutputPort());
  vtkNew<vtkGLSContinuousFeatures> features;
  features->SetInputConnection(variation->GetOutputPort());
  vtkNew<vtkGLSMultiScaleDissimilarity> dissimilarity;
  dissimilarity->SetInputConnection(features->GetOutputPort());
  dissimilarity->SetQueryPointId(1234);
  dissimilarity->Update();
  vtkPolyData* out = dissimilarity->GetPolyDataOutput();
  const auto n = values(out->GetPointData()->GetNormals());
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    ASSERT_NEAR(n[3 * i + 2], 1.0, 1e-12);
  }
  for (const char* name : { "GLSKappa", "GLSTau", "GLSGeometricVariation", "GLSFeature", "GLSDissimilarity" })
  {
    const auto v = pointArray(out, name);
    ASSERT_FALSE(v.empty()) << name;
    for (double x : v)
    {
      ASSERT_NEAR(x, 0.0, 1e-10) << name;
    }
  }
  for (double phi : pointArray(out, "GLSFitness"))
  {
    ASSERT_NEAR(phi, 1.0, 1e-12);
  }
  const auto similar = pointArray(out, "GLSSimilar");
  EXPECT_EQ(std::count(similar.begin(), similar.end(), 1.0), static_cast<long>(c.size()));
}

namespace
{

/// Aborts the filter it observes once progress passes 5%, and counts progress events.
struct Aborter : vtkCommand
{
  static Aborter* New() { return new Aborter; }
  void Execute(vtkObject* caller, unsigned long, void* data) override
  {
    ++this->Calls;
    if (*static_cast<double*>(data) > 0.05)
    {
      static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
    }
  }
  int Calls = 0;
};

template <typename Filter>
void expectAbortLeavesInputOnly(vtkPolyData* input, const char* producedArray)
{
  vtkNew<Filter> f;
  vtkNew<Aborter> aborter;
  f->AddObserver(vtkCommand::ProgressEvent, aborter);
  f->SetNumberOfThreads(2);
  f->SetInputData(input);
  f->Update();
  EXPECT_GT(aborter->Calls, 1) << producedArray;
  EXPECT_EQ(f->GetOutput()->GetPointData()->GetArray(producedArray), nullptr) << producedArray;
  EXPECT_EQ(f->GetOutput()->GetNumberOfPoints(), input->GetNumberOfPoints());
}

} // namespace

TEST(AllFilters, AbortLeavesTheInputWithoutPartialArrays)
{
  const Cloud c = sphere(60000, 1.0);
  auto withNormals = makePolyData(c);
  expectAbortLeavesInputOnly<vtkGLSScaleSpace>(withNormals, "GLSKappa");
  expectAbortLeavesInputOnly<vtkGLSGeometricVariation>(withNormals, "GLSGeometricVariation");
  expectAbortLeavesInputOnly<vtkGLSContinuousFeatures>(withNormals, "GLSFeature");
  expectAbortLeavesInputOnly<vtkGLSMultiScaleDissimilarity>(withNormals, "GLSDissimilarity");
  // Normal estimation: the input's normals stay, no new array replaces them.
  vtkNew<vtkGLSNormalEstimation> f;
  vtkNew<Aborter> aborter;
  f->AddObserver(vtkCommand::ProgressEvent, aborter);
  f->SetInputData(makePolyData(c.points, {}));
  f->Update();
  EXPECT_GT(aborter->Calls, 1);
  EXPECT_EQ(f->GetOutput()->GetPointData()->GetNormals(), nullptr);
}
