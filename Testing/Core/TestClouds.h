// Analytic and seeded-random point clouds with exact normals for the core tests.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstddef>
#include <random>
#include <string>
#include <vector>

namespace glstest
{

struct Cloud
{
  std::vector<double> points;  // interleaved xyz
  std::vector<double> normals; // interleaved xyz
  std::size_t size() const { return points.size() / 3; }
  void add(double x, double y, double z, double nx, double ny, double nz)
  {
    points.insert(points.end(), { x, y, z });
    normals.insert(normals.end(), { nx, ny, nz });
  }
};

/// A patch of the cylinder x^2 + y^2 = r^2 (angles [-a, a], heights [-h, h]) sampled as a scanner does (one point
/// jittered in each cell of a grid of `spacing`), with exact normals, outward (or inward when `inward`).
inline Cloud cylinderPatch(double r, double a, double h, double spacing, unsigned seed, bool inward = false)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(0.0, 1.0);
  const int nu = static_cast<int>(std::ceil(2.0 * a * r / spacing));
  const int nv = static_cast<int>(std::ceil(2.0 * h / spacing));
  const double side = inward ? -1.0 : 1.0;
  Cloud c;
  for (int i = 0; i < nu; ++i)
  {
    for (int j = 0; j < nv; ++j)
    {
      const double u = -a + 2.0 * a * (i + jitter(rng)) / nu, z = -h + 2.0 * h * (j + jitter(rng)) / nv;
      c.add(r * std::cos(u), r * std::sin(u), z, side * std::cos(u), side * std::sin(u), 0.0);
    }
  }
  return c;
}

/// n points on a sphere (Fibonacci lattice), normals outward (or inward when `inward`).
inline Cloud sphere(std::size_t n, double radius, bool inward = false, double cx = 0, double cy = 0, double cz = 0)
{
  Cloud c;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (std::size_t i = 0; i < n; ++i)
  {
    const double z = 1.0 - 2.0 * (static_cast<double>(i) + 0.5) / static_cast<double>(n);
    const double r = std::sqrt(1.0 - z * z);
    const double a = golden * static_cast<double>(i);
    const double nx = r * std::cos(a), ny = r * std::sin(a), nz = z;
    const double s = inward ? -1.0 : 1.0;
    c.add(cx + radius * nx, cy + radius * ny, cz + radius * nz, s * nx, s * ny, s * nz);
  }
  return c;
}

/// A square grid of side `side` with m x m points in the plane z = 0, normals +z.
inline Cloud plane(int m, double side)
{
  Cloud c;
  for (int i = 0; i < m; ++i)
  {
    for (int j = 0; j < m; ++j)
    {
      c.add(side * (i / double(m - 1) - 0.5), side * (j / double(m - 1) - 0.5), 0.0, 0, 0, 1);
    }
  }
  return c;
}

/// z = a x^2 + b y^2 sampled on a jittered grid over [-h, h]^2, with exact normals (+z side), positions perturbed
/// along z by uniform noise of amplitude `noise` and normals by `normalNoise` (then renormalized). Seeded.
inline Cloud paraboloid(int m, double h, double a, double b, double noise, double normalNoise, unsigned seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Cloud c;
  const double step = 2.0 * h / (m - 1);
  for (int i = 0; i < m; ++i)
  {
    for (int j = 0; j < m; ++j)
    {
      const double x = -h + i * step + 0.3 * step * u(rng);
      const double y = -h + j * step + 0.3 * step * u(rng);
      const double z = a * x * x + b * y * y + noise * u(rng);
      double nx = -2 * a * x + normalNoise * u(rng), ny = -2 * b * y + normalNoise * u(rng),
             nz = 1.0 + normalNoise * u(rng);
      const double l = std::sqrt(nx * nx + ny * ny + nz * nz);
      c.add(x, y, z, nx / l, ny / l, nz / l);
    }
  }
  return c;
}

/// n points on the circle of radius r in the plane z = 0 (a 2D curve), normals outward in the plane.
inline Cloud circle2D(std::size_t n, double r)
{
  Cloud c;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double a = 2.0 * M_PI * static_cast<double>(i) / static_cast<double>(n);
    c.add(r * std::cos(a), r * std::sin(a), 0.0, std::cos(a), std::sin(a), 0.0);
  }
  return c;
}

/// The curve y = A sin(w x), x in [x0, x1], n points, z = 0, unit normals on the +y side.
inline Cloud sinusoid2D(std::size_t n, double amplitude, double w, double x0, double x1)
{
  Cloud c;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double x = x0 + (x1 - x0) * static_cast<double>(i) / static_cast<double>(n - 1);
    const double slope = amplitude * w * std::cos(w * x);
    const double l = std::sqrt(1.0 + slope * slope);
    c.add(x, amplitude * std::sin(w * x), 0.0, -slope / l, 1.0 / l, 0.0);
  }
  return c;
}

/// The vertices of an OBJ file ("v x y z" lines); empty if the file cannot be read.
std::vector<double> readObjVertices(const std::string& path);

/// Triangles sampled by area: `count` points uniform over the triangles (corner indices into xyz), each with the
/// normal interpolated (barycentric) from its corners' unit vertex normals and normalized (its triangle's own
/// normal where they cancel), written to points and normals (3 count values each). Deterministic for a given seed.
/// The one sampler of the test and benchmark clouds: sampleObjSurface reads an OBJ for it without VTK, the
/// benchmarks' MeshSampler hands it VTK's meshes.
void sampleTrianglesByArea(const std::vector<double>& xyz, const std::vector<double>& vertexNormals,
  const std::vector<std::array<std::size_t, 3>>& triangles, std::size_t count, std::uint64_t seed, double* points,
  double* normals);

/// An OBJ file's surface sampled by area (sampleTrianglesByArea; polygons fanned into triangles, vertex normals
/// area-weighted from the faces). Empty if the file has no triangle. VTK-free, so that the core's tests and the GPU
/// benchmark run on machines without VTK.
Cloud sampleObjSurface(const std::string& path, std::size_t n, std::uint64_t seed);

/// The diagonal of the bounding box of interleaved xyz triples (the length the relative scales are fractions of).
double boxDiagonal(const std::vector<double>& xyz);

/// Path of a file in Testing/Data (the build passes the source directory in GLS_TEST_DATA_DIR).
std::string dataFile(const std::string& name);

} // namespace glstest
