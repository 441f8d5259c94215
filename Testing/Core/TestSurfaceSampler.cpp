// The test and benchmark clouds' surface sampler (TestClouds.h): points on the triangles, uniform by area, with the
// interpolated unit normals, read from OBJ faces in every index form.
#include "TestClouds.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

using namespace glstest;

TEST(SurfaceSampler, AQuadInEveryFaceFormIsSampledUniformlyWithItsNormal)
{
  // The unit square in z = 0 as one quad (fanned into two triangles) and as two triangles with texture and normal
  // indices: every sample on the square with normal +z, its mean at the centre and a quarter of the samples in each
  // quarter (uniform by area, 20,000 samples: 3 sigma is about 0.009).
  const std::string quad = ::testing::TempDir() + "gls-quad.obj";
  const std::string pair = ::testing::TempDir() + "gls-pair.obj";
  std::ofstream(quad) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
  std::ofstream(pair) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1\nf 1//1 3//1 4//1\n";
  for (const std::string& path : { quad, pair })
  {
    const Cloud c = sampleObjSurface(path, 20000, 7);
    ASSERT_EQ(c.size(), 20000u) << path;
    double mean[2] = { 0, 0 };
    long quarter = 0;
    for (std::size_t i = 0; i < c.size(); ++i)
    {
      const double* p = &c.points[3 * i];
      const double* n = &c.normals[3 * i];
      ASSERT_GE(p[0], 0.0);
      ASSERT_LE(p[0], 1.0);
      ASSERT_GE(p[1], 0.0);
      ASSERT_LE(p[1], 1.0);
      ASSERT_EQ(p[2], 0.0);
      ASSERT_DOUBLE_EQ(n[2], 1.0);
      mean[0] += p[0] / c.size();
      mean[1] += p[1] / c.size();
      quarter += p[0] < 0.5 && p[1] < 0.5 ? 1 : 0;
    }
    EXPECT_NEAR(mean[0], 0.5, 0.01) << path;
    EXPECT_NEAR(mean[1], 0.5, 0.01) << path;
    EXPECT_NEAR(quarter / 20000.0, 0.25, 0.01) << path;
    const Cloud again = sampleObjSurface(path, 20000, 7);
    EXPECT_EQ(again.points, c.points); // deterministic for a seed
  }
  EXPECT_EQ(sampleObjSurface(::testing::TempDir() + "gls-no-such-file.obj", 10, 1).size(), 0u);
  std::remove(quad.c_str());
  std::remove(pair.c_str());
}

TEST(SurfaceSampler, NormalsFollowTheVertexNormalsAcrossATriangle)
{
  // A triangle whose vertex normals differ: a sample's normal is the normalized barycentric blend, so it lies in
  // their cone (every component between the corners' extremes, unit length).
  const std::vector<double> xyz = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
  const double s = 1.0 / std::sqrt(2.0);
  const std::vector<double> normals = { 0, 0, 1, s, 0, s, 0, s, s };
  std::vector<double> p(3 * 1000), n(3 * 1000);
  sampleTrianglesByArea(xyz, normals, { { 0, 1, 2 } }, 1000, 3, p.data(), n.data());
  for (std::size_t i = 0; i < 1000; ++i)
  {
    ASSERT_LE(p[3 * i] + p[3 * i + 1], 1.0 + 1e-15);
    ASSERT_NEAR(n[3 * i] * n[3 * i] + n[3 * i + 1] * n[3 * i + 1] + n[3 * i + 2] * n[3 * i + 2], 1.0, 1e-14);
    ASSERT_GE(n[3 * i + 2], s - 1e-15);
    // Barycentric: the normal's x component follows the weight of corner 1, that is the sample's x.
    const double x = p[3 * i], y = p[3 * i + 1];
    const double blend[3] = { x * s, y * s, (1 - x - y) + (x + y) * s };
    const double l = std::sqrt(blend[0] * blend[0] + blend[1] * blend[1] + blend[2] * blend[2]);
    ASSERT_NEAR(n[3 * i], blend[0] / l, 1e-12);
    ASSERT_NEAR(n[3 * i + 1], blend[1] / l, 1e-12);
  }
}
