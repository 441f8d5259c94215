// vtkGLSScaleProfiles: a sphere's profiles are flat and exact; on the bunny they equal the scale space at the same
// scales; bad selections give clear errors.
#include "FilterTestUtilities.h"

#include "vtkGLSNormalEstimation.h"
#include "vtkGLSGeometricVariation.h"
#include "vtkGLSScaleProfiles.h"
#include "vtkGLSScaleSpace.h"

#include "vtkPointData.h"
#include "vtkTable.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace glstest;

TEST(ScaleProfiles, SphereProfilesAreExact)
{
  const double r = 2.0;
  const Cloud c = sphere(4000, r);
  vtkNew<vtkGLSScaleProfiles> f;
  f->SetInputData(makePolyData(c));
  f->AddPointId(3);
  f->AddPointId(2500);
  f->SetScaleUnitsToAbsolute();
  f->SetMinScale(0.3);
  f->SetMaxScale(2.0);
  f->Update();
  vtkTable* t = f->GetOutputTable();
  ASSERT_EQ(t->GetNumberOfRows(), 200);
  ASSERT_EQ(t->GetNumberOfColumns(), 9);
  const auto scales = values(vtkDataArray::SafeDownCast(t->GetColumnByName("t")));
  EXPECT_EQ(scales.front(), 0.3);
  EXPECT_EQ(scales.back(), 2.0);
  const auto kappa = values(vtkDataArray::SafeDownCast(t->GetColumnByName("t*kappa (2500)")));
  const auto nu = values(vtkDataArray::SafeDownCast(t->GetColumnByName("nu (3)")));
  const auto phi = values(vtkDataArray::SafeDownCast(t->GetColumnByName("phi (3)")));
  for (std::size_t k = 0; k < 200; ++k)
  {
    ASSERT_NEAR(kappa[k], scales[k] / r, 1e-9);
    ASSERT_NEAR(nu[k], 0.0, 1e-12);
    ASSERT_NEAR(phi[k], 1.0, 1e-9);
  }
}

TEST(ScaleProfiles, BunnyProfilesEqualTheScaleSpaceAtTheSameScales)
{
  vtkNew<vtkGLSNormalEstimation> n;
  n->SetInputData(bunnyCloud());
  n->Update();
  vtkNew<vtkGLSScaleSpace> s;
  s->SetInputConnection(n->GetOutputPort());
  vtkNew<vtkGLSGeometricVariation> v;
  v->SetInputConnection(s->GetOutputPort());
  v->Update();
  vtkNew<vtkGLSScaleProfiles> p;
  p->SetInputConnection(n->GetOutputPort());
  p->SetNumberOfScales(20); // the scale space's default scales
  // Downstream of a scale space the profiles still sample their own scales.
  vtkNew<vtkGLSScaleProfiles> fine;
  fine->SetInputConnection(s->GetOutputPort());
  fine->AddPointId(1234);
  fine->Update();
  EXPECT_EQ(fine->GetOutputTable()->GetNumberOfRows(), 200);
  p->AddPointId(1234);
  p->Update();
  vtkTable* t = p->GetOutputTable();
  const auto scales = fieldArray(v->GetPolyDataOutput(), "GLSScales");
  EXPECT_EQ(values(vtkDataArray::SafeDownCast(t->GetColumnByName("t"))), scales);
  const auto kappa = pointArray(v->GetPolyDataOutput(), "GLSKappa");
  const auto nu = pointArray(v->GetPolyDataOutput(), "GLSGeometricVariation");
  const auto pk = values(vtkDataArray::SafeDownCast(t->GetColumnByName("t*kappa (1234)")));
  const auto pn = values(vtkDataArray::SafeDownCast(t->GetColumnByName("nu (1234)")));
  for (std::size_t k = 0; k < 20; ++k)
  {
    EXPECT_TRUE(identical({ pk[k] }, { scales[k] * kappa[1234 * 20 + k] })) << k;
    EXPECT_TRUE(identical({ pn[k] }, { nu[1234 * 20 + k] })) << k;
  }
}

TEST(ScaleProfiles, BadSelectionsGiveClearErrors)
{
  const Cloud c = sphere(300, 1.0);
  vtkNew<vtkGLSScaleProfiles> f;
  auto errors = catchErrors(f);
  f->SetInputData(makePolyData(c));
  f->Update();
  EXPECT_NE(errors->Message.find("No point selected"), std::string::npos) << errors->Message;
  f->AddPointId(300);
  f->Update();
  EXPECT_NE(errors->Message.find("out of range"), std::string::npos) << errors->Message;
}
