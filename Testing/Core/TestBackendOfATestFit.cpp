// A test-only backend for the test-only fit (HeightSpreadMoments.h): the recipe of docs/architecture.md ("How to add a
// backend"), done as far as a test can (the enum value, the engine's branch and the XML entry belong to a real one).
// A backend is a gls::SampleEvaluator: given a run's points (RunPoints: ids and positions), it feeds the sink every
// point's samples in any order, invalid ones at a non-finite position, and stops when the progress callback asks.
// This one runs the host/device loops a device runs (the windowed forms, bit for bit the reference loops) on the
// grid or on the pyramid with the test set's own cells, on the CPU's threads (evaluateEachPoint). Checked against the
// engine's CPU evaluators for the sphere's samples, and against the heights summed by hand for the fit's own value.
#include "HeightSpreadMoments.h"
#include "TestBinning.h"
#include "TestClouds.h"

#include "SampleEvaluators.h" // the evaluator interface (private to the core)

#include "gls/MultiresolutionCellSums.h"
#include "gls/MultiresolutionReferenceWalk.h"
#include "gls/NeighborGrid.h"
#include "gls/ScaleSampling.h"
#include "gls/ScaleSpaceEngine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

using namespace glstest;

namespace
{

/// The test-only backend: the windowed host/device loops of the test set, on the grid (exact) or on the pyramid with
/// the set's cells (multi-resolution).
class WindowedLoopEvaluator : public gls::SampleEvaluator
{
public:
  WindowedLoopEvaluator(const gls::GridView* grid, const gls::MultiresolutionView* pyramid,
    const HeightSpreadMoments::Cell* cells, const gls::EvaluatorBasis& basis, std::vector<double>& spreads)
    : Grid(grid)
    , Pyramid(pyramid)
    , Cells(cells)
    , Basis(basis)
    , Spreads(spreads)
  {
  }

  gls::Backend backend() const override { return gls::Backend::CPU; } // a real backend has its own Backend value

  bool run(const gls::RunPoints& points, gls::ScaleSampleSink& sink, const gls::ParallelOptions& options,
    bool& aborted, std::string&) const override
  {
    const std::size_t S = this->Basis.scaleCount();
    const gls::ScaleBinning& b = this->Basis.binning;
    const double m = this->Basis.minNeighbors;
    this->Spreads.assign(points.count * S, gls::quietNaN<double>());
    std::vector<std::vector<gls::ScaleSample>> spheres(
      static_cast<std::size_t>(gls::resolveThreadCount(options.threads)), std::vector<gls::ScaleSample>(S));
    const HeightSpreadMoments::Sample invalid{ gls::invalidSample<double>(0.0), gls::quietNaN<double>() };
    aborted = !gls::evaluateEachPoint(
      points, S, invalid, options,
      [&](const gls::Vec3& p, int, HeightSpreadMoments::Sample* out) {
        if (this->Grid)
        {
          gls::evaluateAllScalesByWindows<4, HeightSpreadMoments>(*this->Grid, p, b, m, out);
        }
        else
        {
          gls::evaluateAllScalesMultiresolutionByWindows<4, HeightSpreadMoments>(
            *this->Pyramid, this->Cells, p, b, m, out);
        }
      },
      // The sink takes the sphere's samples; the spreads are kept beside them.
      [&](std::uint64_t id, const HeightSpreadMoments::Sample* samples, int thread) {
        std::vector<gls::ScaleSample>& sphere = spheres[static_cast<std::size_t>(thread)];
        for (std::size_t k = 0; k < S; ++k)
        {
          sphere[k] = samples[k].sphere;
          this->Spreads[id * S + k] = samples[k].heightSpread;
        }
        sink.consume(id, sphere.data(), thread);
      });
    return !aborted;
  }

private:
  const gls::GridView* Grid;
  const gls::MultiresolutionView* Pyramid;
  const HeightSpreadMoments::Cell* Cells;
  gls::EvaluatorBasis Basis;
  std::vector<double>& Spreads;
};

/// Keeps every sample a run feeds, by point id.
struct CollectingSink : gls::ScaleSampleSink
{
  CollectingSink(std::size_t points, std::size_t scales)
    : Scales(scales)
    , Samples(points * scales, gls::invalidSample<double>(-1.0))
  {
  }
  void consume(std::uint64_t pointId, const gls::ScaleSample* samples, int) override
  {
    std::copy(samples, samples + this->Scales, &this->Samples[pointId * this->Scales]);
  }
  std::size_t Scales;
  std::vector<gls::ScaleSample> Samples;
};

/// A run over every point of the cloud and one at a non-finite position (the last id), in reverse order, read from
/// positions kept apart (as the engine's points left out of its grid are).
struct ReversedRun
{
  explicit ReversedRun(const Cloud& c)
  {
    const std::size_t n = c.size();
    for (std::size_t i = 0; i < n; ++i)
    {
      this->Positions.push_back({ c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2] });
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    this->Positions.push_back({ nan, 0.0, 0.0 });
    for (std::size_t k = 0; k <= n; ++k)
    {
      this->Order.push_back(static_cast<std::uint32_t>(n - k));
    }
    this->Slots.assign(this->Order.begin(), this->Order.end());
    this->Points.order = this->Order.data();
    this->Points.count = this->Order.size();
    this->Points.slots = this->Slots.data();
    this->Points.rest = this->Positions.data();
  }
  std::vector<gls::Vec3> Positions;
  std::vector<std::uint32_t> Order;
  std::vector<std::uint64_t> Slots;
  gls::RunPoints Points;
};

/// Runs both evaluators and checks: the sphere's samples agree (the same sums in another grouping: to rounding), the
/// spreads are the heights' to `spreadTolerance` t, and the point at a non-finite position is invalid throughout.
/// Returns the largest spread difference, in units of t.
double compareWithCpu(const gls::SampleEvaluator& backend, const gls::SampleEvaluator& cpu, const Cloud& c,
  const std::vector<double>& scales, const std::vector<double>& spreads, double spreadTolerance)
{
  const ReversedRun run(c);
  const std::size_t S = scales.size(), n = c.size();
  gls::ParallelOptions options;
  options.threads = 3;
  options.chunk = 16;
  CollectingSink fromBackend(n + 1, S), fromCpu(n + 1, S);
  bool aborted = false;
  std::string failure;
  EXPECT_TRUE(backend.run(run.Points, fromBackend, options, aborted, failure));
  EXPECT_TRUE(cpu.run(run.Points, fromCpu, options, aborted, failure));
  double worstSpread = 0.0;
  long checked = 0;
  for (std::size_t i = 0; i <= n; ++i)
  {
    for (std::size_t k = 0; k < S; ++k)
    {
      const gls::ScaleSample& a = fromBackend.Samples[i * S + k];
      const gls::ScaleSample& e = fromCpu.Samples[i * S + k];
      // Counts: whole in the exact evaluation, a cell's share of its points in the multi-resolution one.
      EXPECT_NEAR(a.neighbors, e.neighbors, 1e-12 * e.neighbors) << "point " << i << " scale " << k;
      EXPECT_EQ(a.valid, e.valid) << "point " << i << " scale " << k;
      EXPECT_EQ(std::isnan(spreads[i * S + k]), !a.valid) << "point " << i << " scale " << k;
      if (i == n || !a.valid)
      {
        EXPECT_FALSE(i == n && a.valid);
        continue;
      }
      const double t = scales[k];
      EXPECT_NEAR(a.kappa * t, e.kappa * t, 1e-10);
      EXPECT_NEAR(a.tau / t, e.tau / t, 1e-10);
      EXPECT_NEAR(a.phi, e.phi, 1e-10);
      EXPECT_NEAR(gls::dot(a.eta, e.eta), 1.0, 1e-12);
      const gls::Vec3 p{ c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2] };
      worstSpread = std::max(worstSpread, std::abs(spreads[i * S + k] - heightSpreadByHand(c, p, t)) / t);
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
  EXPECT_LT(worstSpread, spreadTolerance);
  return worstSpread;
}

} // namespace

TEST(BackendOfATestFit, ExactOnTheGridAgreesWithTheCpuOnePass)
{
  const Cloud c = paraboloid(60, 1.0, 0.7, 0.3, 0.01, 0.05, 4);
  const std::vector<double> scales = gls::sampleScales(0.05, 0.4, 8, gls::ScaleSampling::Quadratic);
  const TestBinning binning(scales);
  gls::NeighborGrid grid;
  grid.build(c.points.data(), c.normals.data(), c.size(), scales.back() / 4.0);
  const gls::EvaluatorBasis basis{ binning.View, 6.0 };
  std::vector<double> spreads;
  const WindowedLoopEvaluator backend(&grid.view(), nullptr, nullptr, basis, spreads);
  const double worst =
    compareWithCpu(backend, *gls::makeOnePassEvaluator(grid.view(), basis), c, scales, spreads, 1e-9);
  std::printf("test backend, exact: spread against the heights summed by hand %.3g t\n", worst);
}

TEST(BackendOfATestFit, MultiresolutionWithItsOwnCellsAgreesWithTheCpuKernel)
{
  const Cloud c = paraboloid(60, 1.0, 0.7, 0.3, 0.01, 0.05, 4);
  const std::vector<double> scales = gls::sampleScales(0.05, 0.4, 8, gls::ScaleSampling::Quadratic);
  const TestBinning binning(scales);
  gls::ScaleSpaceSettings settings;
  settings.scales = scales;
  settings.evaluation = gls::Evaluation::Multiresolution;
  settings.multiresolution.accuracy = 0.3;
  const gls::ScaleSpaceEngine engine(c.points.data(), c.normals.data(), c.size(), settings);
  const gls::MultiresolutionView& v = engine.pyramid().view();
  const std::vector<HeightSpreadMoments::Cell> cells = gls::summedCellsOf<HeightSpreadMoments>(v);
  const gls::EvaluatorBasis basis{ binning.View, 6.0 };
  std::vector<double> spreads;
  const WindowedLoopEvaluator backend(nullptr, &v, cells.data(), basis, spreads);
  // The spread of cells taken whole is the exact one's to the evaluation's accuracy (TestFitWithAnExtraSum: 3.7e-4 t).
  const double worst =
    compareWithCpu(backend, *gls::makeMultiresolutionEvaluator(v, basis), c, scales, spreads, 1e-3);
  std::printf("test backend, multi-resolution: spread against the heights summed by hand %.3g t\n", worst);
}

TEST(BackendOfATestFit, StopsWhenTheProgressCallbackAsks)
{
  const Cloud c = paraboloid(40, 1.0, 0.7, 0.3, 0.01, 0.05, 4);
  const std::vector<double> scales = gls::sampleScales(0.05, 0.4, 4, gls::ScaleSampling::Quadratic);
  const TestBinning binning(scales);
  gls::NeighborGrid grid;
  grid.build(c.points.data(), c.normals.data(), c.size(), scales.back() / 4.0);
  std::vector<double> spreads;
  const WindowedLoopEvaluator backend(&grid.view(), nullptr, nullptr, { binning.View, 6.0 }, spreads);
  const ReversedRun run(c);
  CollectingSink sink(c.size() + 1, scales.size());
  gls::ParallelOptions options;
  options.threads = 2;
  options.chunk = 8;
  options.progress = [](double) { return true; };
  bool aborted = false;
  std::string failure;
  EXPECT_FALSE(backend.run(run.Points, sink, options, aborted, failure));
  EXPECT_TRUE(aborted);
  EXPECT_TRUE(failure.empty());
}
