// vtkGLSAdaptiveBandwidth and vtkGLSProjection: the paper's Figure 9 acceptance case (a wavy closed curve with
// noise on positions, on normals, on both, and a clean part), analytic shapes, reuse, errors, abort, threads.
#include "FilterTestUtilities.h"
#include "NoisyCurve.h"

#include "vtkGLSAdaptiveBandwidth.h"
#include "vtkGLSGeometricVariation.h"
#include "vtkGLSProjection.h"

#include "vtkAlgorithm.h"
#include "vtkCommand.h"
#include "vtkIntArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

using namespace glstest;

namespace
{

/// The adaptive-bandwidth settings of the Figure 9 case (absolute scales; the curve's radius is about 1).
/// The Figure 9 curve's scale range (a few spacings up to a third of the waves' length, as the filter's
/// documentation advises) and smoothing radius, the same as the denoising benchmark's.
void configureBandwidth(vtkGLSAdaptiveBandwidth* f)
{
  f->SetScaleUnitsToAbsolute();
  f->SetMinScale(0.004);
  f->SetMaxScale(0.15);
  f->SetNumberOfScales(40);
  f->SetScaleSamplingToLogarithmic();
  f->SetSmoothingRadius(0.06);
}

std::vector<double> points(vtkPolyData* pd)
{
  return values(pd->GetPoints()->GetData());
}

double regionMedian(const std::vector<double>& values, const NoisyCurve& curve, int region)
{
  std::vector<double> v;
  for (std::size_t i = 0; i < curve.size(); ++i)
  {
    if (curve.Region[i] == region)
    {
      v.push_back(values[i]);
    }
  }
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

} // namespace

TEST(AdaptiveBandwidthFilter, FollowsTheNoiseOfEachRegion)
{
  const NoisyCurve curve{ NoisyCurveSpec() };
  vtkNew<vtkGLSAdaptiveBandwidth> f;
  configureBandwidth(f);
  f->SetInputData(makePolyData(curve.Points, curve.Normals));
  f->Update();
  const std::vector<double> b = pointArray(f->GetPolyDataOutput(), "GLSBandwidth");
  const std::vector<double> raw = pointArray(f->GetPolyDataOutput(), "GLSRawBandwidth");
  ASSERT_EQ(b.size(), curve.size());
  const double a = regionMedian(b, curve, 0), bb = regionMedian(b, curve, 1), c = regionMedian(b, curve, 2),
               d = regionMedian(raw, curve, 3);
  // Strong noise (A) needs a larger support than weak noise (B); noisy normals (C) too; the clean part keeps the
  // smallest scale.
  EXPECT_GT(a, 2.0 * bb);
  EXPECT_GT(c, 2.0 * bb);
  EXPECT_GT(bb, 2.0 * d);
  EXPECT_DOUBLE_EQ(d, 0.004);
  for (double v : b)
  {
    EXPECT_TRUE(v >= 0.004 * (1 - 1e-12) && v <= 0.15 * (1 + 1e-12)) << v;
  }
  EXPECT_EQ(fieldArray(f->GetPolyDataOutput(), "GLSScales").size(), 40u);
}

TEST(AdaptiveBandwidthFilter, UpstreamVariationGivesTheSameBandwidth)
{
  const NoisyCurve curve{ NoisyCurveSpec() };
  auto input = makePolyData(curve.Points, curve.Normals);
  vtkNew<vtkGLSAdaptiveBandwidth> fused;
  configureBandwidth(fused);
  fused->SetInputData(input);
  fused->Update();
  vtkNew<vtkGLSGeometricVariation> variation;
  variation->SetScaleUnitsToAbsolute();
  variation->SetMinScale(0.004);
  variation->SetMaxScale(0.15);
  variation->SetNumberOfScales(40);
  variation->SetScaleSamplingToLogarithmic();
  variation->SetInputData(input);
  vtkNew<vtkGLSAdaptiveBandwidth> reused;
  reused->SetInputConnection(variation->GetOutputPort());
  reused->SetSmoothingRadius(0.06);
  reused->SetScaleUnitsToAbsolute();
  reused->SetMaxScale(7.0); // ignored: the upstream scales are used
  reused->Update();
  EXPECT_EQ(pointArray(fused->GetPolyDataOutput(), "GLSBandwidth"), pointArray(reused->GetPolyDataOutput(), "GLSBandwidth"));
}

TEST(ProjectionFilter, Figure9CaseDenoisesTheNoisyPartsAndLeavesTheCleanPart)
{
  const NoisyCurve curve{ NoisyCurveSpec() };
  auto input = makePolyData(curve.Points, curve.Normals);
  const NoisyCurve::Scores before = curve.score(curve.Points.data(), curve.Normals.data());

  vtkNew<vtkGLSAdaptiveBandwidth> bandwidth;
  configureBandwidth(bandwidth);
  bandwidth->SetInputData(input);
  vtkNew<vtkGLSProjection> adaptive;
  adaptive->SetInputConnection(bandwidth->GetOutputPort());
  adaptive->Update();
  EXPECT_EQ(adaptive->GetLastScaleMode(), vtkGLSProjection::BANDWIDTH_ARRAY);
  vtkPolyData* out = adaptive->GetPolyDataOutput();
  const NoisyCurve::Scores after = curve.score(points(out).data(), pointArray(out, "Normals").data());

  // Noisy positions (A, B): RMS distance to the clean curve down at least 3 times; noisy normals: RMS angle down
  // at least 3 times where only the normals are noisy (C), 2.5 times where both are (A; measured 2.6); the clean
  // part far from the noise moves by less than 5% of the spacing.
  EXPECT_LT(after.positionRms[0] * 3.0, before.positionRms[0]);
  EXPECT_LT(after.positionRms[1] * 3.0, before.positionRms[1]);
  EXPECT_LT(after.normalRmsDegrees[0] * 2.5, before.normalRmsDegrees[0]);
  EXPECT_LT(after.normalRmsDegrees[2] * 3.0, before.normalRmsDegrees[2]);
  EXPECT_LT(after.cleanInteriorMaxMove, 0.05 * curve.spacing());
  EXPECT_LT(after.positionRms[3], 0.1 * curve.spacing());

  // Against every single global scale: the adaptive result has a lower RMS distance than the scale with the lowest
  // one (measured 0.680 vs 0.691 spacing, a small margin) and clearly better normals (2.45 vs 3.50 degrees).
  double bestRms = 1e300, bestAngle = 0, bestScale = 0;
  for (double t : { 0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.09, 0.1, 0.11, 0.12, 0.15 })
  {
    vtkNew<vtkGLSProjection> global;
    global->SetScaleModeToFixedScale();
    global->SetScaleUnitsToAbsolute();
    global->SetScale(t);
    global->SetInputData(input);
    global->Update();
    EXPECT_EQ(global->GetLastScaleMode(), vtkGLSProjection::FIXED_SCALE);
    const NoisyCurve::Scores s =
      curve.score(points(global->GetPolyDataOutput()).data(), pointArray(global->GetPolyDataOutput(), "Normals").data());
    if (s.totalPositionRms < bestRms)
    {
      bestRms = s.totalPositionRms;
      bestAngle = s.totalNormalRmsDegrees;
      bestScale = t;
    }
  }
  std::cout << "adaptive: RMS distance " << after.totalPositionRms << ", RMS normal angle " << after.totalNormalRmsDegrees
            << " deg; best global scale " << bestScale << ": " << bestRms << ", " << bestAngle << " deg\n";
  EXPECT_LT(after.totalPositionRms, bestRms) << "best global scale " << bestScale;
  EXPECT_LT(after.totalNormalRmsDegrees * 1.3, bestAngle) << "best global scale " << bestScale;
}

TEST(ProjectionFilter, NoisySphereProjectsOntoTheSphereWithRadialNormals)
{
  Cloud c = sphere(6000, 1.0);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0.0, 0.01);
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    const double k = 1.0 + g(rng);
    for (int a = 0; a < 3; ++a)
    {
      c.points[3 * i + a] *= k;
    }
  }
  vtkNew<vtkGLSProjection> f;
  f->SetInputData(makePolyData(c));
  f->SetScaleUnitsToAbsolute();
  f->SetScale(0.25);
  f->Update();
  vtkPolyData* out = f->GetPolyDataOutput();
  const std::vector<double> p = points(out), n = pointArray(out, "Normals"), d = pointArray(out, "GLSDisplacement");
  double before = 0, after = 0;
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    const double r0 = std::sqrt(c.points[3 * i] * c.points[3 * i] + c.points[3 * i + 1] * c.points[3 * i + 1] +
      c.points[3 * i + 2] * c.points[3 * i + 2]);
    const double r1 = std::sqrt(p[3 * i] * p[3 * i] + p[3 * i + 1] * p[3 * i + 1] + p[3 * i + 2] * p[3 * i + 2]);
    before += (r0 - 1) * (r0 - 1);
    after += (r1 - 1) * (r1 - 1);
    EXPECT_NEAR((n[3 * i] * p[3 * i] + n[3 * i + 1] * p[3 * i + 1] + n[3 * i + 2] * p[3 * i + 2]) / r1, 1.0, 2e-3);
    const double moved = std::sqrt(std::pow(p[3 * i] - c.points[3 * i], 2) +
      std::pow(p[3 * i + 1] - c.points[3 * i + 1], 2) + std::pow(p[3 * i + 2] - c.points[3 * i + 2], 2));
    EXPECT_NEAR(d[i], moved, 1e-15);
  }
  EXPECT_LT(std::sqrt(after / before), 0.2);
  EXPECT_EQ(out->GetPointData()->GetNormals(), out->GetPointData()->GetArray("Normals"));
  EXPECT_EQ(out->GetPoints()->GetDataType(), VTK_DOUBLE);
  EXPECT_EQ(out->GetNumberOfVerts(), static_cast<vtkIdType>(c.size()));
  auto iterations = vtkIntArray::SafeDownCast(out->GetPointData()->GetArray("GLSProjectionIterations"));
  ASSERT_NE(iterations, nullptr);
  EXPECT_LT(iterations->GetRange()[1], 50);
}

TEST(ProjectionFilter, BitwiseIdenticalForAnyThreadCountAndClearErrors)
{
  const NoisyCurve curve{ NoisyCurveSpec() };
  auto input = makePolyData(curve.Points, curve.Normals);
  std::vector<double> reference;
  for (int threads : { 1, 2, 5 })
  {
    vtkNew<vtkGLSProjection> f;
    f->SetInputData(input);
    f->SetNumberOfThreads(threads);
    f->SetScaleUnitsToAbsolute();
    f->SetScale(0.05);
    f->Update();
    const std::vector<double> p = points(f->GetPolyDataOutput());
    if (reference.empty())
    {
      reference = p;
    }
    EXPECT_EQ(p, reference);
  }

  vtkNew<vtkGLSProjection> missing;
  missing->SetInputData(input);
  missing->SetScaleModeToBandwidthArray();
  auto errors = catchErrors(missing);
  missing->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Message.find("No bandwidth array"), std::string::npos) << errors->Message;

  vtkNew<vtkGLSProjection> zero;
  zero->SetInputData(input);
  zero->SetScale(0.0);
  auto zeroErrors = catchErrors(zero);
  zero->Update();
  EXPECT_EQ(zeroErrors->Count, 1);
  EXPECT_NE(zeroErrors->Message.find("Scale must be positive"), std::string::npos) << zeroErrors->Message;

  auto noNormals = makePolyData(curve.Points, {});
  vtkNew<vtkGLSProjection> unoriented;
  unoriented->SetInputData(noNormals);
  auto normalErrors = catchErrors(unoriented);
  unoriented->Update();
  EXPECT_EQ(normalErrors->Count, 1);

  auto wrongSize = makePolyData(curve.Points, curve.Normals);
  vtkNew<vtkDoubleArray> shortBandwidth;
  shortBandwidth->SetName("GLSBandwidth");
  shortBandwidth->SetNumberOfTuples(10);
  wrongSize->GetPointData()->AddArray(shortBandwidth);
  vtkNew<vtkGLSProjection> misSized;
  misSized->SetInputData(wrongSize);
  auto sizeErrors = catchErrors(misSized);
  misSized->Update();
  EXPECT_EQ(sizeErrors->Count, 1);
  EXPECT_NE(sizeErrors->Message.find("must have 1 component"), std::string::npos) << sizeErrors->Message;
}

TEST(ProjectionFilter, AbortLeavesNoPartialArrays)
{
  const Cloud c = sphere(40000, 1.0);
  for (int which = 0; which < 2; ++which)
  {
    vtkSmartPointer<vtkAlgorithm> f;
    if (which == 0)
    {
      f = vtkSmartPointer<vtkGLSProjection>::New();
    }
    else
    {
      f = vtkSmartPointer<vtkGLSAdaptiveBandwidth>::New();
    }
    f->SetInputDataObject(makePolyData(c));
    struct Aborter : vtkCommand
    {
      static Aborter* New() { return new Aborter; }
      void Execute(vtkObject* caller, unsigned long, void* data) override
      {
        if (*static_cast<double*>(data) > 0.05)
        {
          static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
        }
      }
    };
    vtkNew<Aborter> aborter;
    f->AddObserver(vtkCommand::ProgressEvent, aborter);
    f->Update();
    vtkPolyData* out = vtkPolyData::SafeDownCast(f->GetOutputDataObject(0));
    EXPECT_EQ(out->GetNumberOfPoints(), 40000);
    EXPECT_EQ(out->GetPointData()->GetArray("GLSDisplacement"), nullptr);
    EXPECT_EQ(out->GetPointData()->GetArray("GLSBandwidth"), nullptr);
  }
}
