// vtkGLSScaleSpaceImage: the scale-space images of analytic curves (sinusoid, flower, circle) against their analytic
// curvature and inflection points; invariance to the plane's orientation; clear errors on bad input.
#include "FilterTestUtilities.h"

#include "vtkGLSScaleSpaceImage.h"

#include "vtkCellArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

using namespace glstest;

namespace
{

/// A polyline through the points (closed: the last id repeats the first), without normals.
vtkSmartPointer<vtkPolyData> makeCurve(const std::vector<double>& xyz, bool closed)
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  const vtkIdType n = static_cast<vtkIdType>(xyz.size() / 3);
  std::vector<vtkIdType> ids;
  for (vtkIdType i = 0; i < n; ++i)
  {
    pts->InsertNextPoint(&xyz[3 * i]);
    ids.push_back(i);
  }
  if (closed)
  {
    ids.push_back(0);
  }
  vtkNew<vtkCellArray> lines;
  lines->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  pd->SetPoints(pts);
  pd->SetLines(lines);
  return pd;
}

std::vector<double> sinusoid(int n, double amplitude)
{
  std::vector<double> xyz;
  for (int i = 0; i < n; ++i)
  {
    const double x = 4.0 * vtkMath::Pi() * i / (n - 1);
    xyz.insert(xyz.end(), { x, amplitude * std::sin(x), 0.0 });
  }
  return xyz;
}

constexpr double FlowerAmplitude = 0.25;

/// r(theta) = 1 + a cos(5 theta), counter-clockwise, n points (not repeated).
std::vector<double> flower(int n)
{
  std::vector<double> xyz;
  for (int i = 0; i < n; ++i)
  {
    const double th = 2.0 * vtkMath::Pi() * i / n;
    const double r = 1.0 + FlowerAmplitude * std::cos(5.0 * th);
    xyz.insert(xyz.end(), { r * std::cos(th), r * std::sin(th), 0.0 });
  }
  return xyz;
}

/// Signed curvature of the polar curve (> 0 where convex): (r^2 + 2 r'^2 - r r'') / (r^2 + r'^2)^(3/2).
double flowerCurvatureNumerator(double th)
{
  const double a = FlowerAmplitude;
  const double r = 1 + a * std::cos(5 * th), r1 = -5 * a * std::sin(5 * th), r2 = -25 * a * std::cos(5 * th);
  return r * r + 2 * r1 * r1 - r * r2;
}
double flowerCurvature(double th)
{
  const double a = FlowerAmplitude;
  const double r = 1 + a * std::cos(5 * th), r1 = -5 * a * std::sin(5 * th);
  return flowerCurvatureNumerator(th) / std::pow(r * r + r1 * r1, 1.5);
}

/// Cumulative arclength of the polyline through the points (closed: plus the closing segment).
std::vector<double> polylineArclength(const std::vector<double>& xyz, bool closed)
{
  const std::size_t n = xyz.size() / 3;
  std::vector<double> s(1, 0.0);
  for (std::size_t i = 1; i < n + (closed ? 1 : 0); ++i)
  {
    s.push_back(s.back() + std::sqrt(vtkMath::Distance2BetweenPoints(&xyz[3 * (i - 1)], &xyz[3 * (i % n)])));
  }
  return s;
}

/// The curve parameter u (x for the sinusoid, theta for the flower) at arclength s: linear between the curve points
/// u[i], as the filter interpolates.
double parameterAt(const std::vector<double>& arclength, const std::vector<double>& u, double s)
{
  const auto it = std::upper_bound(arclength.begin(), arclength.end(), s);
  const std::size_t j = std::min<std::size_t>(
    std::max<std::ptrdiff_t>(it - arclength.begin() - 1, 0), arclength.size() - 2);
  const double w = (s - arclength[j]) / (arclength[j + 1] - arclength[j]);
  return u[j] + w * (u[j + 1] - u[j]);
}

double simpson(const std::function<double(double)>& f, double a, double b, int n)
{
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i)
  {
    sum += f(a + i * h) * (i % 2 ? 4 : 2);
  }
  return sum * h / 3;
}

vtkImageData* runImage(vtkGLSScaleSpaceImage* f, vtkPolyData* input)
{
  f->SetInputData(input);
  f->Update();
  return f->GetImageOutput();
}

/// The crossing points lying on the image row y (points on that row's horizontal edges; the contour's points are
/// single precision).
std::vector<double> crossingsOnRow(vtkPolyData* crossings, double y)
{
  std::vector<double> xs;
  for (vtkIdType i = 0; i < crossings->GetNumberOfPoints(); ++i)
  {
    double p[3];
    crossings->GetPoint(i, p);
    if (std::abs(p[1] - y) <= 1e-6 * std::abs(y))
    {
      xs.push_back(p[0]);
    }
  }
  std::sort(xs.begin(), xs.end());
  return xs;
}

std::vector<double> imageArray(vtkImageData* image, const char* name)
{
  return values(image->GetPointData()->GetArray(name));
}

std::vector<double> imageField(vtkImageData* image, const char* name)
{
  return values(image->GetFieldData()->GetArray(name));
}

double maxAbs(const std::vector<double>& v)
{
  double m = 0;
  for (double x : v)
  {
    if (std::isfinite(x))
    {
      m = std::max(m, std::abs(x));
    }
  }
  return m;
}

} // namespace

TEST(ScaleSpaceImage, SinusoidCrossingsAreTheInflectionPoints)
{
  const int n = 2000;
  const std::vector<double> xyz = sinusoid(n, 1.0);
  vtkNew<vtkGLSScaleSpaceImage> f;
  f->SetNumberOfArclengthSamples(0); // one column per curve point
  f->SetScaleUnitsToAbsolute();
  f->SetMinScale(0.05);
  f->SetMaxScale(1.0);
  f->SetNumberOfScales(39);
  vtkImageData* image = runImage(f, makeCurve(xyz, false));
  EXPECT_FALSE(f->GetLastCurveClosed());

  // Geometry of the image: x = arclength (0 to L), y = t (equally spaced from MinScale to MaxScale).
  const std::vector<double> s = polylineArclength(xyz, false);
  const double L = s.back();
  const double analyticL = simpson([](double x) { return std::sqrt(1 + std::cos(x) * std::cos(x)); }, 0,
    4 * vtkMath::Pi(), 20000);
  EXPECT_NEAR(L, analyticL, 1e-5 * analyticL);
  EXPECT_NEAR(f->GetLastCurveLength(), L, 1e-12 * L);
  int dims[3];
  double origin[3], spacing[3];
  image->GetDimensions(dims);
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  EXPECT_EQ(dims[0], n);
  EXPECT_EQ(dims[1], 39);
  EXPECT_EQ(dims[2], 1);
  EXPECT_EQ(origin[0], 0.0);
  EXPECT_EQ(origin[1], 0.05);
  EXPECT_NEAR(spacing[0], L / (n - 1), 1e-14 * L);
  EXPECT_NEAR(spacing[1], 0.025, 1e-15);
  const std::vector<double> scales = imageField(image, "GLSScales");
  ASSERT_EQ(scales.size(), 39u);
  for (int k = 0; k < 39; ++k)
  {
    EXPECT_NEAR(scales[k], origin[1] + k * spacing[1], 1e-14);
  }

  // Kappa at the smallest scale against the analytic curvature (left normals: kappa = +A sin x / (1+A^2cos^2x)^1.5).
  std::vector<double> xs(n);
  for (int i = 0; i < n; ++i)
  {
    xs[i] = xyz[3 * i];
  }
  const std::vector<double> kappa = imageArray(image, "GLSKappa");
  const std::vector<double> scaled = imageArray(image, "GLSScaledKappa");
  const std::vector<double> nu = imageArray(image, "GLSNu");
  ASSERT_EQ(kappa.size(), static_cast<std::size_t>(n * 39));
  double worst = 0.0;
  for (int i = 0; i < n; ++i)
  {
    const double x = parameterAt(s, xs, i * spacing[0]);
    if (x < 0.2 || x > 4 * vtkMath::Pi() - 0.2)
    {
      continue;
    }
    const double c = std::cos(x);
    const double expected = std::sin(x) / std::pow(1 + c * c, 1.5);
    worst = std::max(worst, std::abs(kappa[i] - expected));
    EXPECT_NEAR(scaled[i], 0.05 * kappa[i], 1e-15);
    EXPECT_TRUE(std::isfinite(nu[i]) && nu[i] >= 0.0);
  }
  EXPECT_LT(worst, 0.01) << "kappa at t = 0.05 vs the analytic curvature";
  std::printf("sinusoid: max |kappa - analytic| at t = 0.05: %.3g\n", worst);

  // The zero crossings: the three interior inflection points x = pi, 2 pi, 3 pi, at every scale (point symmetry
  // about each inflection keeps kappa = 0 there while the ball does not reach the curve's ends).
  vtkPolyData* crossings = f->GetCrossingsOutput();
  ASSERT_GT(crossings->GetNumberOfLines(), 0);
  const double dx = 4 * vtkMath::Pi() / (n - 1);
  int found[3] = { 0, 0, 0 };
  double lo[3] = { 1e9, 1e9, 1e9 }, hi[3] = { 0, 0, 0 };
  for (vtkIdType i = 0; i < crossings->GetNumberOfPoints(); ++i)
  {
    double p[3];
    crossings->GetPoint(i, p);
    ASSERT_TRUE(std::isfinite(p[0]) && std::isfinite(p[1]));
    EXPECT_EQ(p[2], 0.0);
    const double x = parameterAt(s, xs, p[0]);
    if (x < 0.5 || x > 4 * vtkMath::Pi() - 0.5)
    {
      continue; // near the curve's ends (one-sided fits)
    }
    const int k = static_cast<int>(std::lround(x / vtkMath::Pi()));
    ASSERT_GE(k, 1);
    ASSERT_LE(k, 3);
    EXPECT_NEAR(x, k * vtkMath::Pi(), 3 * dx) << "crossing at t = " << p[1];
    ++found[k - 1];
    lo[k - 1] = std::min(lo[k - 1], p[1]);
    hi[k - 1] = std::max(hi[k - 1], p[1]);
  }
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_GT(found[k], 0) << "no crossing at x = " << k + 1 << " pi";
    EXPECT_NEAR(lo[k], 0.05, 1e-7) << "the crossing line at " << k + 1 << " pi spans every scale";
    EXPECT_NEAR(hi[k], 1.0, 1e-7);
  }
  // On the smallest scale's row: exactly one crossing near each inflection.
  int interior = 0;
  for (double a : crossingsOnRow(crossings, 0.05))
  {
    const double x = parameterAt(s, xs, a);
    interior += x > 0.5 && x < 4 * vtkMath::Pi() - 0.5;
  }
  EXPECT_EQ(interior, 3);
}

TEST(ScaleSpaceImage, FlowerInflectionsAnnihilateAtLargeScales)
{
  // Analytic inflections of r = 1 + 0.25 cos(5 theta): sign changes of the curvature's numerator.
  int analyticInflections = 0;
  const int fine = 100000;
  for (int i = 0; i < fine; ++i)
  {
    const double a = 2 * vtkMath::Pi() * i / fine, b = 2 * vtkMath::Pi() * (i + 1) / fine;
    analyticInflections += (flowerCurvatureNumerator(a) > 0) != (flowerCurvatureNumerator(b) > 0);
  }
  ASSERT_EQ(analyticInflections, 10);

  const int n = 3000;
  const std::vector<double> xyz = flower(n);
  vtkNew<vtkGLSScaleSpaceImage> f;
  f->SetNumberOfArclengthSamples(0); // one column per curve point
  f->SetScaleUnitsToAbsolute();
  f->SetMinScale(0.02);
  f->SetMaxScale(1.0);
  f->SetNumberOfScales(50);
  vtkImageData* image = runImage(f, makeCurve(xyz, true));
  EXPECT_TRUE(f->GetLastCurveClosed());
  int dims[3];
  image->GetDimensions(dims);
  ASSERT_EQ(dims[0], n + 1); // one column per curve point, plus s = L
  ASSERT_EQ(dims[1], 50);
  const std::vector<double> kappa = imageArray(image, "GLSKappa");
  const std::vector<double> s = polylineArclength(xyz, true);
  std::vector<double> theta(n + 1);
  for (int i = 0; i <= n; ++i)
  {
    theta[i] = 2 * vtkMath::Pi() * i / n;
  }
  const double ds = image->GetSpacing()[0];
  double worst = 0.0;
  int signChanges = 0;
  for (int i = 0; i < dims[0] - 1; ++i)
  {
    EXPECT_EQ(kappa[i], kappa[i]) << "no NaN at t = 0.02";
    const double expected = flowerCurvature(parameterAt(s, theta, i * ds));
    if (std::abs(expected) > 0.5)
    {
      EXPECT_GT(kappa[i] * expected, 0.0) << "sign at column " << i;
      worst = std::max(worst, std::abs(kappa[i] / expected - 1));
    }
    signChanges += (kappa[i] > 0) != (kappa[(i + 1) % (dims[0] - 1)] > 0);
  }
  EXPECT_LT(worst, 0.03) << "relative kappa error at t = 0.02 away from inflections";
  std::printf("flower: max relative kappa error at t = 0.02 (|kappa| > 0.5): %.3g\n", worst);
  EXPECT_EQ(signChanges, analyticInflections);
  EXPECT_EQ(kappa[dims[0] - 1], kappa[0]) << "the column at s = L repeats s = 0";

  // At t = 1 (the curve's mean radius) the crossings have annihilated: kappa > 0 everywhere.
  const std::size_t top = static_cast<std::size_t>(dims[0]) * (dims[1] - 1);
  for (int i = 0; i < dims[0]; ++i)
  {
    ASSERT_GT(kappa[top + i], 0.0) << "column " << i;
  }
  vtkPolyData* crossings = f->GetCrossingsOutput();
  EXPECT_EQ(crossingsOnRow(crossings, 0.02).size(), 10u);
  double highest = 0.0;
  for (vtkIdType i = 0; i < crossings->GetNumberOfPoints(); ++i)
  {
    highest = std::max(highest, crossings->GetPoint(i)[1]);
  }
  EXPECT_LT(highest, 1.0);
  EXPECT_GT(highest, 0.02);
  std::printf("flower: %lld crossing polylines, highest crossing at t = %.3f\n",
    static_cast<long long>(crossings->GetNumberOfLines()), highest);
}

TEST(ScaleSpaceImage, CircleHasConstantCurvatureAndNoCrossings)
{
  const double r = 2.0;
  std::vector<double> xyz;
  for (int i = 0; i < 600; ++i)
  {
    const double th = -2 * vtkMath::Pi() * i / 600; // clockwise: the outward orientation must not depend on it
    xyz.insert(xyz.end(), { r * std::cos(th), r * std::sin(th), 0.0 });
  }
  vtkNew<vtkGLSScaleSpaceImage> f;
  f->SetScaleUnitsToAbsolute();
  f->SetMinScale(0.1);
  f->SetMaxScale(3.0);
  f->SetNumberOfScales(30);
  f->SetNumberOfArclengthSamples(257);
  vtkImageData* image = runImage(f, makeCurve(xyz, true));
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(dims[0], 257);
  EXPECT_NEAR(image->GetSpacing()[0] * 256, f->GetLastCurveLength(), 1e-12);
  const std::vector<double> kappa = imageArray(image, "GLSKappa");
  const std::vector<double> scaled = imageArray(image, "GLSScaledKappa");
  const std::vector<double> nu = imageArray(image, "GLSNu");
  const std::vector<double> scales = imageField(image, "GLSScales");
  for (std::size_t j = 0; j < kappa.size(); ++j)
  {
    ASSERT_NEAR(kappa[j], 1 / r, 1e-9) << j;
    ASSERT_NEAR(scaled[j], scales[j / 257] / r, 1e-9) << j;
    ASSERT_NEAR(nu[j], 0.0, 1e-12) << j;
  }
  EXPECT_EQ(f->GetCrossingsOutput()->GetNumberOfLines(), 0);
  EXPECT_EQ(f->GetCrossingsOutput()->GetNumberOfPoints(), 0);
}

TEST(ScaleSpaceImage, UndefinedFitsAreNaNAndCrossingsStayFinite)
{
  // Scales below the sample spacing hold fewer than 3 neighbours: NaN rows; the crossings skip them.
  const std::vector<double> xyz = sinusoid(400, 1.0);
  vtkNew<vtkGLSScaleSpaceImage> f;
  f->SetNumberOfArclengthSamples(0); // one column per curve point
  f->SetScaleUnitsToAbsolute();
  f->SetMinScale(0.001);
  f->SetMaxScale(0.5);
  f->SetNumberOfScales(20);
  vtkImageData* image = runImage(f, makeCurve(xyz, false));
  const std::vector<double> kappa = imageArray(image, "GLSKappa");
  const std::vector<double> nu = imageArray(image, "GLSNu");
  for (int i = 0; i < 400; ++i)
  {
    EXPECT_TRUE(std::isnan(kappa[i]) && std::isnan(nu[i])) << i;
    EXPECT_TRUE(std::isfinite(kappa[400 * 19 + i])) << i;
  }
  vtkPolyData* crossings = f->GetCrossingsOutput();
  EXPECT_GT(crossings->GetNumberOfLines(), 0);
  for (vtkIdType i = 0; i < crossings->GetNumberOfPoints(); ++i)
  {
    double p[3];
    crossings->GetPoint(i, p);
    EXPECT_TRUE(std::isfinite(p[0]) && std::isfinite(p[1])) << i;
  }
}

TEST(ScaleSpaceImage, TiltedPlaneGivesTheSameImage)
{
  // A rotation whose image of +z has a positive largest component (the open-curve orientation convention), plus an
  // offset.
  double axis[3] = { 1.0, 2.0, 3.0 };
  vtkMath::Normalize(axis);
  const double angle = 0.7, c = std::cos(angle), sn = std::sin(angle);
  double R[3][3];
  for (int a = 0; a < 3; ++a)
  {
    for (int b = 0; b < 3; ++b)
    {
      R[a][b] = (a == b ? c : 0.0) + (1 - c) * axis[a] * axis[b];
    }
  }
  R[0][1] -= sn * axis[2];
  R[0][2] += sn * axis[1];
  R[1][0] += sn * axis[2];
  R[1][2] -= sn * axis[0];
  R[2][0] -= sn * axis[1];
  R[2][1] += sn * axis[0];
  ASSERT_GT(R[2][2], std::max(std::abs(R[0][2]), std::abs(R[1][2])));
  const double offset[3] = { 3.0, -2.0, 5.0 };

  for (bool closed : { false, true })
  {
    const std::vector<double> xyz = closed ? flower(1500) : sinusoid(1500, 1.0);
    std::vector<double> tilted(xyz.size());
    for (std::size_t i = 0; i < xyz.size(); i += 3)
    {
      for (int a = 0; a < 3; ++a)
      {
        tilted[i + a] = offset[a] + R[a][0] * xyz[i] + R[a][1] * xyz[i + 1] + R[a][2] * xyz[i + 2];
      }
    }
    vtkNew<vtkGLSScaleSpaceImage> flat, tilt;
    for (vtkGLSScaleSpaceImage* f : { flat.Get(), tilt.Get() })
    {
      f->SetScaleUnitsToAbsolute();
      f->SetMinScale(0.03);
      f->SetMaxScale(0.8);
      f->SetNumberOfScales(25);
    }
    vtkImageData* a = runImage(flat, makeCurve(xyz, closed));
    vtkImageData* b = runImage(tilt, makeCurve(tilted, closed));
    EXPECT_NEAR(a->GetSpacing()[0], b->GetSpacing()[0], 1e-12);
    for (const char* name : { "GLSKappa", "GLSScaledKappa", "GLSNu" })
    {
      const std::vector<double> va = imageArray(a, name), vb = imageArray(b, name);
      ASSERT_EQ(va.size(), vb.size());
      const double scale = maxAbs(va);
      ASSERT_GT(scale, 0.0);
      double worst = 0.0;
      for (std::size_t j = 0; j < va.size(); ++j)
      {
        ASSERT_EQ(std::isnan(va[j]), std::isnan(vb[j])) << name << " " << j;
        if (!std::isnan(va[j]))
        {
          worst = std::max(worst, std::abs(va[j] - vb[j]) / scale);
        }
      }
      EXPECT_LT(worst, 1e-9) << name << (closed ? " (closed)" : " (open)");
      std::printf("tilted %s: %s max difference / max |value| = %.3g\n", closed ? "flower" : "sinusoid", name, worst);
    }
    EXPECT_EQ(flat->GetCrossingsOutput()->GetNumberOfLines(), tilt->GetCrossingsOutput()->GetNumberOfLines());
  }
}

TEST(ScaleSpaceImage, BadInputGivesClearErrors)
{
  vtkNew<vtkGLSScaleSpaceImage> f;
  f->SetNumberOfArclengthSamples(0); // one column per curve point
  auto errors = catchErrors(f);
  f->SetScaleUnitsToAbsolute();
  f->SetMinScale(0.1);
  f->SetMaxScale(0.5);
  f->SetNumberOfScales(5);

  f->SetInputData(makeCurve({ 0, 0, 0, 1, 0, 0 }, false));
  f->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Message.find("at least 3"), std::string::npos) << errors->Message;

  f->SetInputData(makeCurve({ 1, 1, 1, 1, 1, 1, 1, 1, 1 }, false));
  f->Update();
  EXPECT_EQ(errors->Count, 2);
  EXPECT_NE(errors->Message.find("length is zero"), std::string::npos) << errors->Message;

  std::vector<double> helix;
  for (int i = 0; i < 200; ++i)
  {
    helix.insert(helix.end(), { std::cos(0.1 * i), std::sin(0.1 * i), 0.05 * i });
  }
  f->SetInputData(makeCurve(helix, false));
  f->Update();
  EXPECT_EQ(errors->Count, 3);
  EXPECT_NE(errors->Message.find("not planar"), std::string::npos) << errors->Message;

  // The helix with normals (pointing away from its axis) is fitted in 3D.
  auto withNormals = makeCurve(helix, false);
  vtkNew<vtkDoubleArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  for (int i = 0; i < 200; ++i)
  {
    normals->InsertNextTuple3(std::cos(0.1 * i), std::sin(0.1 * i), 0.0);
  }
  withNormals->GetPointData()->SetNormals(normals);
  f->SetInputData(withNormals);
  f->Update();
  EXPECT_EQ(errors->Count, 3) << errors->Message;
  EXPECT_EQ(f->GetImageOutput()->GetNumberOfPoints(), 200 * 5);

  f->SetInputData(makeCurve(sinusoid(100, 1.0), false));
  f->AddScale(0.1);
  f->AddScale(0.2);
  f->AddScale(0.4);
  f->Update();
  EXPECT_EQ(errors->Count, 4);
  EXPECT_NE(errors->Message.find("equally spaced"), std::string::npos) << errors->Message;
  f->RemoveAllScales();
  f->AddScale(0.1);
  f->AddScale(0.2);
  f->AddScale(0.3);
  f->Update();
  EXPECT_EQ(errors->Count, 4) << errors->Message;
  EXPECT_EQ(f->GetImageOutput()->GetDimensions()[1], 3);
}
