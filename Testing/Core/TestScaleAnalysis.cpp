// Pertinent scales, continuous features, scale priors and the multi-scale dissimilarity, against hand-computed
// values and the analytic sphere.
#include "CollectingSink.h"
#include "TestClouds.h"

#include "gls/Descriptors.h"
#include "gls/ScaleAnalysis.h"
#include "gls/ScaleSampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

TEST(ScaleSampling, ProducesTheDocumentedSequences)
{
  const auto lin = gls::sampleScales(1.0, 3.0, 3, gls::ScaleSampling::Linear);
  EXPECT_DOUBLE_EQ(lin[1], 2.0);
  const auto quad = gls::sampleScales(1.0, 3.0, 3, gls::ScaleSampling::Quadratic);
  EXPECT_DOUBLE_EQ(quad[1], 1.5);
  const auto lg = gls::sampleScales(1.0, 4.0, 3, gls::ScaleSampling::Logarithmic);
  EXPECT_DOUBLE_EQ(lg[1], 2.0);
  EXPECT_EQ(lg[2], 4.0);
  EXPECT_EQ(gls::sampleScales(0.5, 0.5, 1, gls::ScaleSampling::Linear), std::vector<double>{ 0.5 });
  EXPECT_TRUE(gls::checkScaleRange(0.1, 1.0, 20).empty());
  EXPECT_FALSE(gls::checkScaleRange(0.0, 1.0, 20).empty());
  EXPECT_FALSE(gls::checkScaleRange(2.0, 1.0, 20).empty());
  EXPECT_FALSE(gls::checkScaleRange(0.1, 1.0, 0).empty());
  EXPECT_FALSE(gls::checkScaleRange(1.0, 1.0, 2).empty());
  EXPECT_FALSE(gls::checkScaleList({ 0.1, 0.1 }).empty());
  EXPECT_FALSE(gls::checkScaleList({}).empty());
  EXPECT_TRUE(gls::checkScaleList({ 0.1, 0.2 }).empty());
}

TEST(ScaleAnalysis, PertinentScalesAreTheLowestLocalMinima)
{
  const double nu[] = { 5, 3, 4, 1, 1, 2, 0.5, 0.7, NAN, 0.1, 0.2 };
  const double t[] = { 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11 };
  double out[4];
  // Minima: index 1 (3), 3 (1, flat bottom counted once), 6 (0.5); index 9 is next to NaN.
  ASSERT_EQ(gls::pertinentScales(nu, t, 11, 4, out), 3);
  EXPECT_EQ(out[0], 2);
  EXPECT_EQ(out[1], 4);
  EXPECT_EQ(out[2], 7);
  ASSERT_EQ(gls::pertinentScales(nu, t, 11, 2, out), 2);
  EXPECT_EQ(out[0], 4); // the two lowest (1 and 0.5), by increasing scale
  EXPECT_EQ(out[1], 7);
}

namespace
{
/// Samples whose tau, kappa and phi name their scale index (tau = k, kappa = 10 k, phi = k / 100).
std::vector<gls::ScaleSample> IndexedSamples(int count)
{
  std::vector<gls::ScaleSample> samples(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k)
  {
    samples[static_cast<std::size_t>(k)].tau = k;
    samples[static_cast<std::size_t>(k)].kappa = 10.0 * k;
    samples[static_cast<std::size_t>(k)].phi = k / 100.0;
  }
  return samples;
}
}

TEST(ScaleAnalysis, SummaryTakesThePertinentScaleOfLowestNu)
{
  // The sequence of PertinentScalesAreTheLowestLocalMinima: minima at indices 1 (3), 3 (1) and 6 (0.5).
  const double nu[] = { 5, 3, 4, 1, 1, 2, 0.5, 0.7, NAN, 0.1, 0.2 };
  const double t[] = { 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11 };
  const auto samples = IndexedSamples(11);
  const gls::ScaleSummary s = gls::summarizeScales(samples.data(), nu, t, 11);
  double pertinent[11];
  EXPECT_EQ(s.pertinentCount, gls::pertinentScales(nu, t, 11, 11, pertinent));
  EXPECT_EQ(s.pertinentCount, 3);
  // Not index 9 (nu 0.1 is lower, but next to NaN it is no pertinent minimum).
  EXPECT_EQ(s.stableIndex, 6);
  EXPECT_EQ(s.stableScale, 7.0);
  EXPECT_EQ(s.tau, 6.0);
  EXPECT_EQ(s.kappa, 60.0);
  EXPECT_EQ(s.phi, 0.06);
  EXPECT_EQ(s.maxVariation, 5.0);
  EXPECT_EQ(s.maxVariationScale, 1.0);
}

TEST(ScaleAnalysis, SummaryWithoutAnInnerMinimumTakesTheLowestNu)
{
  const double t[] = { 1, 2, 3, 4 };
  const auto samples = IndexedSamples(4);
  const double rising[] = { 0.1, 0.2, 0.3, 0.4 };
  gls::ScaleSummary s = gls::summarizeScales(samples.data(), rising, t, 4);
  EXPECT_EQ(s.pertinentCount, 0);
  EXPECT_EQ(s.stableScale, 1.0);
  EXPECT_EQ(s.maxVariationScale, 4.0);
  // A flat nu (a sphere: rounding noise around 1e-20) goes to the smallest scale, and its largest nu too.
  const double flat[] = { 2e-20, 1e-20, 3e-20, 1e-20 };
  s = gls::summarizeScales(samples.data(), flat, t, 4);
  EXPECT_EQ(s.pertinentCount, 0);
  EXPECT_EQ(s.stableScale, 1.0);
  EXPECT_EQ(s.tau, 0.0);
  const double undefinedStart[] = { NAN, NAN, 0.3, 0.2 };
  s = gls::summarizeScales(samples.data(), undefinedStart, t, 4);
  EXPECT_EQ(s.stableScale, 4.0);
  EXPECT_EQ(s.maxVariation, 0.3);
  EXPECT_EQ(s.maxVariationScale, 3.0);
  const double none[] = { NAN, NAN, NAN, NAN };
  s = gls::summarizeScales(samples.data(), none, t, 4);
  EXPECT_EQ(s.stableIndex, -1);
  EXPECT_EQ(s.pertinentCount, 0);
  for (double v : { s.stableScale, s.tau, s.kappa, s.phi, s.maxVariation, s.maxVariationScale })
  {
    EXPECT_TRUE(std::isnan(v));
  }
}

TEST(ScaleAnalysis, ContinuousFeatureIsTheNormalizedTrapezoidIntegral)
{
  const double t[] = { 1, 2, 4 };
  const double constant[] = { 0.3, 0.3, 0.3 };
  EXPECT_NEAR(gls::continuousFeature(constant, t, 3, 0.5, gls::FeatureMeasure::Scale), std::tanh(0.6), 1e-15);
  EXPECT_NEAR(gls::continuousFeature(constant, t, 3, 0.5, gls::FeatureMeasure::LogScale), std::tanh(0.6), 1e-15);
  const double ramp[] = { 0.0, 1.0, 0.0 };
  const double a = std::tanh(1.0);
  EXPECT_NEAR(gls::continuousFeature(ramp, t, 3, 1.0, gls::FeatureMeasure::Scale), (0.5 * a + 1.0 * a) / 3.0, 1e-15);
  EXPECT_NEAR(gls::continuousFeature(ramp, t, 3, 1.0, gls::FeatureMeasure::LogScale), a / 2.0, 1e-15);
  const double withNaN[] = { 0.2, NAN, 0.2 };
  EXPECT_TRUE(std::isnan(gls::continuousFeature(withNaN, t, 3, 1.0, gls::FeatureMeasure::Scale)));
}

TEST(ScaleAnalysis, ContinuousFeatureTakesTanhWithinAnUlpOfOne)
{
  // One scale: f = tanh(nu / sigma), formed through one exponential; within 2.3e-16 of std::tanh from 0 through
  // the values where e^(2x) overflows, 1 at infinity, NaN for NaN.
  const double t[] = { 1.0 };
  double worst = 0.0;
  for (double x = 0.0; x < 400.0; x = x < 1e-12 ? 1e-12 : x * 1.01)
  {
    const double f = gls::continuousFeature(&x, t, 1, 1.0, gls::FeatureMeasure::Scale);
    worst = std::max(worst, std::fabs(f - std::tanh(x)));
  }
  EXPECT_LE(worst, 2.3e-16);
  const double infinite = INFINITY, nan = NAN;
  EXPECT_EQ(gls::continuousFeature(&infinite, t, 1, 1.0, gls::FeatureMeasure::Scale), 1.0);
  EXPECT_TRUE(std::isnan(gls::continuousFeature(&nan, t, 1, 1.0, gls::FeatureMeasure::Scale)));
}

TEST(ScaleAnalysis, PriorWeightsAreNormalized)
{
  const std::vector<double> t = { 1, 2, 4, 8 };
  std::string why;
  const auto box = gls::scalePrior(t, gls::ScalePriorShape::Box, 1.5, 8.0, why);
  EXPECT_EQ(box, (std::vector<double>{ 0.0, 1.0 / 3, 1.0 / 3, 1.0 / 3 }));
  const auto g = gls::scalePrior(t, gls::ScalePriorShape::LogGaussian, 1.0, 8.0, why);
  double sum = 0;
  for (double v : g)
  {
    sum += v;
  }
  EXPECT_NEAR(sum, 1.0, 1e-15);
  EXPECT_NEAR(g[1] / g[2], 1.0, 1e-12); // symmetric about sqrt(8) in log t
  EXPECT_GT(g[1], g[0]);
  EXPECT_TRUE(gls::scalePrior(t, gls::ScalePriorShape::Box, 20.0, 30.0, why).empty());
  EXPECT_FALSE(why.empty());
}

TEST(ScaleAnalysis, DissimilarityIsZeroOnASphereAndMatchesEquation6)
{
  const glstest::Cloud c = glstest::sphere(3000, 1.0);
  const std::vector<double> scales = { 0.3, 0.6, 0.9 };
  const glstest::CollectingSink s = glstest::runScaleSpace(c.points, c.normals, scales);
  std::string why;
  const auto h = gls::scalePrior(scales, gls::ScalePriorShape::Box, 0.0, 1.0, why);
  EXPECT_NEAR(gls::multiScaleDissimilarity(&s.at(0, 0), &s.at(1234, 0), scales, h), 0.0, 1e-18);

  gls::ScaleSample a = s.at(0, 0), b = s.at(0, 0);
  b.tau += 0.03;
  b.kappa += 0.5;
  b.phi -= 0.1;
  const double t = 0.3;
  EXPECT_NEAR(gls::pairDissimilarity(a, b, t), std::pow(0.03 / t, 2) + std::pow(0.5 * t, 2) + 0.01, 1e-15);
  gls::ScaleSample invalid = a;
  invalid.valid = false;
  EXPECT_TRUE(std::isnan(gls::pairDissimilarity(a, invalid, t)));
}
