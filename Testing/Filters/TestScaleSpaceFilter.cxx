// vtkGLSScaleSpace: analytic sphere and plane, scale parameters and units, agreement with the core engine on the
// bunny, array options, bad input.
#include "CollectingSink.h"
#include "FilterTestUtilities.h"

#include "vtkGLSNormalEstimation.h"
#include "vtkGLSScaleSpace.h"

#include "vtkIntArray.h"
#include "vtkPointData.h"

#include "gls/ScaleSampling.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace glstest;

TEST(ScaleSpaceFilter, SphereGivesExactDescriptorsAtEveryScale)
{
  const double r = 2.0;
  const Cloud c = sphere(5000, r);
  vtkNew<vtkGLSScaleSpace> f;
  f->SetInputData(makePolyData(c));
  f->SetScaleUnitsToAbsolute();
  f->SetMinScale(0.3);
  f->SetMaxScale(1.5);
  f->SetNumberOfScales(6);
  f->SetScaleSamplingToLinear();
  f->Update();
  vtkPolyData* out = f->GetPolyDataOutput();
  const std::vector<double> scales = fieldArray(out, "GLSScales");
  ASSERT_EQ(scales, gls::sampleScales(0.3, 1.5, 6, gls::ScaleSampling::Linear));
  const auto kappa = pointArray(out, "GLSKappa");
  const auto tau = pointArray(out, "GLSTau");
  const auto phi = pointArray(out, "GLSFitness");
  const auto dkappa = pointArray(out, "GLSdKappa");
  const auto eta = pointArray(out, "GLSEta");
  ASSERT_EQ(kappa.size(), c.size() * 6);
  ASSERT_EQ(eta.size(), c.size() * 18);
  for (std::size_t i = 0; i < c.size(); i += 13)
  {
    for (std::size_t k = 0; k < 6; ++k)
    {
      EXPECT_NEAR(kappa[i * 6 + k], 1.0 / r, 1e-9);
      EXPECT_NEAR(tau[i * 6 + k], 0.0, 1e-10);
      EXPECT_NEAR(phi[i * 6 + k], 1.0, 1e-9);
      EXPECT_NEAR(dkappa[i * 6 + k], 0.0, 1e-7);
      EXPECT_NEAR(eta[i * 18 + 3 * k + 2], c.normals[3 * i + 2], 1e-9); // scale-major 3-vectors
    }
  }
  vtkDataArray* k = out->GetPointData()->GetArray("GLSKappa");
  EXPECT_STREQ(k->GetComponentName(0), "t=0.3");
  EXPECT_STREQ(out->GetPointData()->GetArray("GLSEta")->GetComponentName(5), "t=0.54 z");
  EXPECT_NE(out->GetPointData()->GetArray("GLSNeighborCount"), nullptr);
}

TEST(ScaleSpaceFilter, PlaneGivesZeroCurvatureWithRelativeScales)
{
  const Cloud c = plane(50, 2.0);
  vtkNew<vtkGLSScaleSpace> f;
  f->SetInputData(makePolyData(c));
  f->SetMinScale(0.05); // relative to the diagonal 2 sqrt(2)
  f->SetMaxScale(0.2);
  f->SetNumberOfScales(3);
  f->Update();
  const std::vector<double> scales = fieldArray(f->GetPolyDataOutput(), "GLSScales");
  ASSERT_EQ(scales.size(), 3u);
  EXPECT_NEAR(scales[0], 0.05 * 2 * std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(scales[2], 0.2 * 2 * std::sqrt(2.0), 1e-14);
  const auto kappa = pointArray(f->GetPolyDataOutput(), "GLSKappa");
  const auto tau = pointArray(f->GetPolyDataOutput(), "GLSTau");
  for (std::size_t i = 0; i < kappa.size(); ++i)
  {
    ASSERT_NEAR(kappa[i], 0.0, 1e-10);
    ASSERT_NEAR(tau[i], 0.0, 1e-12);
  }
}

TEST(ScaleSpaceFilter, BunnyMatchesTheCoreEngineBitwise)
{
  vtkNew<vtkGLSNormalEstimation> normals;
  normals->SetInputData(bunnyCloud());
  vtkNew<vtkGLSScaleSpace> f;
  f->SetInputConnection(normals->GetOutputPort());
  f->Update();
  vtkPolyData* out = f->GetPolyDataOutput();
  const std::vector<double> scales = fieldArray(out, "GLSScales");
  ASSERT_EQ(scales.size(), 20u);
  double b[6];
  out->GetBounds(b);
  const double diag = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
    (b[5] - b[4]) * (b[5] - b[4]));
  EXPECT_NEAR(scales.front(), 0.008 * diag, 1e-15);
  EXPECT_NEAR(scales.back(), 0.08 * diag, 1e-15);

  // The filter computes on the coordinates from the low corner of the input's bounds (vtkGLSCloud::Anchor).
  std::vector<double> xyz = readObjVertices(dataFile("stanford-bunny.obj"));
  for (std::size_t i = 0; i < xyz.size(); ++i)
  {
    xyz[i] -= b[2 * (i % 3)];
  }
  const std::vector<double> nrm = values(out->GetPointData()->GetNormals());
  const CollectingSink core = runScaleSpace(xyz, nrm, scales, 1);
  const auto kappa = pointArray(out, "GLSKappa");
  const auto dtau = pointArray(out, "GLSdTau");
  const auto deta = pointArray(out, "GLSdEta");
  const auto count = pointArray(out, "GLSNeighborCount");
  int valid = 0;
  for (std::size_t i = 0; i < xyz.size() / 3; i += 11)
  {
    for (std::size_t k = 0; k < 20; ++k)
    {
      const gls::ScaleSample& s = core.at(i, k);
      ASSERT_EQ(count[i * 20 + k], s.neighbors);
      if (!s.valid)
      {
        ASSERT_TRUE(std::isnan(kappa[i * 20 + k]));
        continue;
      }
      ++valid;
      ASSERT_EQ(kappa[i * 20 + k], s.kappa);
      ASSERT_EQ(dtau[i * 20 + k], s.dtau);
      ASSERT_EQ(deta[i * 60 + 3 * k + 1], s.deta.y);
    }
  }
  EXPECT_GT(valid, 60000);
}

TEST(ScaleSpaceFilter, ExplicitScalesAndArrayOptions)
{
  const Cloud c = sphere(2000, 1.0);
  vtkNew<vtkGLSScaleSpace> f;
  f->SetInputData(makePolyData(c));
  f->SetScaleUnitsToAbsolute();
  f->AddScale(0.4);
  f->AddScale(0.9);
  f->StoreEtaOff();
  f->StoreDerivativesOff();
  f->StoreNeighborCountOff();
  f->Update();
  EXPECT_EQ(fieldArray(f->GetPolyDataOutput(), "GLSScales"), (std::vector<double>{ 0.4, 0.9 }));
  vtkPointData* pd = f->GetOutput()->GetPointData();
  EXPECT_EQ(pd->GetArray("GLSEta"), nullptr);
  EXPECT_EQ(pd->GetArray("GLSdTau"), nullptr);
  EXPECT_EQ(pd->GetArray("GLSdEta"), nullptr);
  EXPECT_EQ(pd->GetArray("GLSNeighborCount"), nullptr);
  ASSERT_NE(pd->GetArray("GLSKappa"), nullptr);
  EXPECT_EQ(pd->GetArray("GLSKappa")->GetNumberOfComponents(), 2);
}

TEST(ScaleSpaceFilter, BadParametersAndInputGiveClearErrors)
{
  const Cloud c = sphere(500, 1.0);
  struct Case
  {
    const char* what;
    double minScale, maxScale;
    int count;
    const char* expect;
  };
  const Case cases[] = { { "zero min", 0.0, 0.1, 10, "MinScale" }, { "negative min", -1.0, 0.1, 10, "MinScale" },
    { "min > max", 0.2, 0.1, 10, "MaxScale" }, { "no scales", 0.01, 0.1, 0, "NumberOfScales" },
    { "NaN max", 0.01, std::nan(""), 10, "MaxScale" } };
  for (const Case& cs : cases)
  {
    vtkNew<vtkGLSScaleSpace> f;
    auto errors = catchErrors(f);
    f->SetInputData(makePolyData(c));
    f->SetMinScale(cs.minScale);
    f->SetMaxScale(cs.maxScale);
    f->SetNumberOfScales(cs.count);
    f->Update();
    EXPECT_EQ(errors->Count, 1) << cs.what;
    EXPECT_NE(errors->Message.find(cs.expect), std::string::npos) << cs.what << ": " << errors->Message;
    EXPECT_EQ(f->GetOutput()->GetPointData()->GetArray("GLSKappa"), nullptr);
  }
  {
    vtkNew<vtkGLSScaleSpace> f;
    auto errors = catchErrors(f);
    f->AddScale(0.2);
    f->AddScale(0.1);
    f->SetInputData(makePolyData(c));
    f->Update();
    EXPECT_NE(errors->Message.find("increasing"), std::string::npos) << errors->Message;
  }
  {
    vtkNew<vtkGLSScaleSpace> f;
    auto errors = catchErrors(f);
    f->SetInputData(makePolyData(c.points, {}));
    f->Update();
    EXPECT_NE(errors->Message.find("no normals"), std::string::npos) << errors->Message;
  }
  {
    vtkNew<vtkGLSScaleSpace> f;
    auto errors = catchErrors(f);
    auto pd = makePolyData(c.points, {});
    vtkNew<vtkDoubleArray> bad;
    bad->SetName("Normals");
    bad->SetNumberOfComponents(2);
    bad->SetNumberOfTuples(500);
    bad->Fill(1.0);
    pd->GetPointData()->AddArray(bad);
    f->SetInputData(pd);
    f->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Normals");
    f->Update();
    EXPECT_NE(errors->Message.find("expected 3 components"), std::string::npos) << errors->Message;
  }
  {
    vtkNew<vtkGLSScaleSpace> f;
    auto errors = catchErrors(f);
    f->SetInputData(makePolyData(std::vector<double>{}, {}));
    f->Update();
    EXPECT_NE(errors->Message.find("no points"), std::string::npos) << errors->Message;
  }
}

TEST(ScaleSpaceFilter, AbortLeavesNoPartialArrays)
{
  const Cloud c = sphere(40000, 1.0);
  vtkNew<vtkGLSScaleSpace> f;
  f->SetInputData(makePolyData(c));
  struct Aborter : vtkCommand
  {
    static Aborter* New() { return new Aborter; }
    void Execute(vtkObject* caller, unsigned long, void* data) override
    {
      if (*static_cast<double*>(data) > 0.1)
      {
        static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
      }
      ++this->Calls;
    }
    int Calls = 0;
  };
  vtkNew<Aborter> aborter;
  f->AddObserver(vtkCommand::ProgressEvent, aborter);
  f->Update();
  EXPECT_GT(aborter->Calls, 1);
  EXPECT_EQ(f->GetOutput()->GetPointData()->GetArray("GLSKappa"), nullptr);
  EXPECT_EQ(f->GetOutput()->GetNumberOfPoints(), 40000);
}

TEST(ScaleSpaceFilter, BackendFallbackWarnsOnceAndRecordsTheCpu)
{
  const Cloud c = sphere(3000, 1.0);
  auto input = makePolyData(c);
  vtkNew<vtkGLSScaleSpace> cpu;
  cpu->SetMinScale(0.05); // every fit defined (the default 0.8% is below this sphere's spacing: another warning)
  cpu->SetBackendToCPU();
  cpu->SetInputData(input);
  cpu->Update();
  EXPECT_STREQ(cpu->GetLastBackendUsed(), "CPU");
  vtkAbstractArray* recorded = cpu->GetOutput()->GetFieldData()->GetAbstractArray("GLSBackend");
  ASSERT_NE(recorded, nullptr);
  EXPECT_EQ(recorded->GetVariantValue(0).ToString(), "CPU");

  for (int backend : { vtkGLSScaleFilterBase::BACKEND_CUDA, vtkGLSScaleFilterBase::BACKEND_AUTO })
  {
    vtkNew<vtkGLSScaleSpace> f;
    auto warnings = vtkSmartPointer<ErrorCatcher>::New();
    f->AddObserver(vtkCommand::WarningEvent, warnings);
    f->SetMinScale(0.05);
    f->SetBackend(backend);
    f->SetInputData(input);
    f->Update();
    f->Modified();
    f->Update();
    const std::string used = f->GetLastBackendUsed();
    if (used == "CUDA")
    {
      continue; // a machine with a usable device: the cuda-labelled tests compare the numbers
    }
    EXPECT_EQ(used, "CPU");
    EXPECT_EQ(f->GetOutput()->GetFieldData()->GetAbstractArray("GLSBackend")->GetVariantValue(0).ToString(), "CPU");
    // CUDA asked explicitly: exactly one warning naming the reason; Auto: silent.
    EXPECT_EQ(warnings->Count, backend == vtkGLSScaleFilterBase::BACKEND_CUDA ? 1 : 0) << warnings->Message;
    if (backend == vtkGLSScaleFilterBase::BACKEND_CUDA)
    {
      EXPECT_NE(warnings->Message.find("CUDA requested but not available"), std::string::npos);
    }
    EXPECT_TRUE(identical(pointArray(f->GetPolyDataOutput(), "GLSKappa"), pointArray(cpu->GetPolyDataOutput(), "GLSKappa")));
    EXPECT_TRUE(identical(pointArray(f->GetPolyDataOutput(), "GLSdEta"), pointArray(cpu->GetPolyDataOutput(), "GLSdEta")));
  }
}

TEST(ScaleSpaceFilter, PrincipalCurvaturesOnACylinderWhenAsked)
{
  // A cylinder of radius 1 at scales of 4 and 5% of it: k1 = 1 around it, k2 = 0 along the axis (d2 = z), H = 1/2,
  // K = 0, shape index 1/2 (a ridge), curvedness 1/sqrt(2). Off by default; the exact evaluation under Auto.
  const Cloud c = cylinderPatch(1.0, 0.3, 0.3, 0.0045, 3);
  vtkNew<vtkGLSScaleSpace> f;
  f->SetInputData(makePolyData(c));
  f->SetScaleUnitsToAbsolute();
  f->AddScale(0.04);
  f->AddScale(0.05);
  f->Update();
  EXPECT_EQ(f->GetPolyDataOutput()->GetPointData()->GetArray("GLSK1"), nullptr);
  f->StorePrincipalCurvaturesOn();
  f->Update();
  EXPECT_STREQ(f->GetLastEvaluationUsed(), "Exact");
  vtkPolyData* out = f->GetPolyDataOutput();
  const std::size_t S = 2;
  const auto k1 = pointArray(out, "GLSK1"), k2 = pointArray(out, "GLSK2");
  const auto d1 = pointArray(out, "GLSPrincipalDirection1"), d2 = pointArray(out, "GLSPrincipalDirection2");
  const auto H = pointArray(out, "GLSMeanCurvature"), K = pointArray(out, "GLSGaussianCurvature");
  const auto shape = pointArray(out, "GLSShapeIndex"), curved = pointArray(out, "GLSCurvedness");
  const auto kappa = pointArray(out, "GLSKappa");
  ASSERT_EQ(k1.size(), c.size() * S);
  ASSERT_EQ(d2.size(), c.size() * S * 3);
  EXPECT_STREQ(out->GetPointData()->GetArray("GLSPrincipalDirection1")->GetComponentName(4), "t=0.05 y");
  long checked = 0;
  for (std::size_t i = 0; i < c.size(); i += 17)
  {
    const double u = std::atan2(c.points[3 * i + 1], c.points[3 * i]), z = c.points[3 * i + 2];
    if (std::abs(u) > 0.15 || std::abs(z) > 0.15)
    {
      continue;
    }
    for (std::size_t k = 0; k < S; ++k)
    {
      const std::size_t o = i * S + k;
      EXPECT_NEAR(k1[o], 1.0, 0.03); // pointwise, at about 250 points in the smaller ball
      EXPECT_NEAR(k2[o], 0.0, 0.03);
      EXPECT_GT(std::abs(d2[3 * o + 2]), std::cos(2.0 * 3.14159265358979 / 180.0)); // along the axis
      EXPECT_LT(std::abs(d1[3 * o + 2]), std::sin(2.0 * 3.14159265358979 / 180.0));
      EXPECT_NEAR(H[o], 0.5 * (k1[o] + k2[o]), 1e-12);
      EXPECT_NEAR(H[o], kappa[o], 0.01); // the sphere's compromise, to the fit's accuracy
      EXPECT_NEAR(K[o], k1[o] * k2[o], 1e-12);
      EXPECT_NEAR(shape[o], 0.5, 0.02);
      EXPECT_NEAR(curved[o], std::sqrt(0.5), 0.02);
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
  // The multi-resolution evaluation: the same curvatures to its accuracy (t |k - k_exact| within 0.01).
  f->SetEvaluationToMultiresolution();
  f->Update();
  EXPECT_STREQ(f->GetLastEvaluationUsed(), "Multiresolution");
  const auto mk1 = pointArray(f->GetPolyDataOutput(), "GLSK1"), mk2 = pointArray(f->GetPolyDataOutput(), "GLSK2");
  ASSERT_EQ(mk1.size(), k1.size());
  for (std::size_t o = 0; o < k1.size(); o += 7)
  {
    if (std::isfinite(k1[o]))
    {
      EXPECT_NEAR(mk1[o] * 0.05, k1[o] * 0.05, 0.01);
      EXPECT_NEAR(mk2[o] * 0.05, k2[o] * 0.05, 0.01);
    }
  }
}

TEST(ScaleSpaceFilter, PrincipalCurvaturesCountInTheBudget)
{
  const Cloud c = sphere(150, 1.0);
  // 150 points at 4,000 scales: 48 MiB of stored descriptors, 103 MiB with the curvatures' 12 doubles more.
  for (bool curvatures : { false, true })
  {
    vtkNew<vtkGLSScaleSpace> f;
    auto errors = catchErrors(f);
    f->SetInputData(makePolyData(c));
    f->SetScaleUnitsToAbsolute();
    f->SetMinScale(0.8);
    f->SetMaxScale(1.5);
    f->SetNumberOfScales(4000);
    f->SetMemoryBudget(80.0);
    f->SetStorePrincipalCurvatures(curvatures);
    f->Update();
    EXPECT_EQ(errors->Count, curvatures ? 1 : 0) << errors->Message;
    EXPECT_EQ(f->GetOutput()->GetPointData()->GetArray("GLSKappa") != nullptr, !curvatures);
  }
}
