// Parametric surfaces with exact normals and their true principal curvatures (from the fundamental forms), sampled
// as a scanner samples (one point jittered per cell of a parameter grid): the oracle of the principal curvatures'
// tests (TestShapeOperator.cpp) and of their accuracy benchmark (glsCurvatureBenchmark).
#pragma once

#include "TestClouds.h"

#include "gls/ShapeOperator.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace glstest
{

constexpr double kPi = 3.14159265358979323846;

/// A parametric surface X(u, v) with its outward unit normal (the orientation the curvatures' signs refer to).
struct Surface
{
  std::string name;
  std::function<gls::Vec3(double, double)> X;
  std::function<gls::Vec3(double, double)> normal;
};

inline gls::Vec3 unit(const gls::Vec3& v)
{
  return (1.0 / std::sqrt(gls::squaredNorm(v))) * v;
}

/// The true principal curvatures and directions at (u, v): the eigenvalues of -I^{-1} II (positive on a sphere with
/// outward normals), from the parametrization's derivatives by central differences (step 1e-4: errors near 1e-8).
inline gls::PrincipalCurvatures truth(const Surface& s, double u, double v)
{
  const double h = 1e-4;
  const gls::Vec3 Xu = (0.5 / h) * (s.X(u + h, v) - s.X(u - h, v));
  const gls::Vec3 Xv = (0.5 / h) * (s.X(u, v + h) - s.X(u, v - h));
  const gls::Vec3 X0 = s.X(u, v);
  const gls::Vec3 Xuu = (1.0 / (h * h)) * (s.X(u + h, v) - 2.0 * X0 + s.X(u - h, v));
  const gls::Vec3 Xvv = (1.0 / (h * h)) * (s.X(u, v + h) - 2.0 * X0 + s.X(u, v - h));
  const gls::Vec3 Xuv =
    (0.25 / (h * h)) * (s.X(u + h, v + h) - s.X(u + h, v - h) - s.X(u - h, v + h) + s.X(u - h, v - h));
  const gls::Vec3 n = s.normal(u, v);
  const double E = gls::dot(Xu, Xu), F = gls::dot(Xu, Xv), G = gls::dot(Xv, Xv);
  const double L = gls::dot(Xuu, n), M = gls::dot(Xuv, n), N = gls::dot(Xvv, n);
  // A = -I^{-1} II.
  const double det = E * G - F * F;
  const double a00 = -(G * L - F * M) / det, a01 = -(G * M - F * N) / det;
  const double a10 = -(E * M - F * L) / det, a11 = -(E * N - F * M) / det;
  const double mean = 0.5 * (a00 + a11), disc = std::sqrt(std::max(0.0, 0.25 * (a00 - a11) * (a00 - a11) + a01 * a10));
  gls::PrincipalCurvatures pc;
  pc.k1 = mean + disc;
  pc.k2 = mean - disc;
  // The eigenvector of k1 in (u, v), the longer of two forms.
  const double p1 = a01, q1 = pc.k1 - a00, p2 = pc.k1 - a11, q2 = a10;
  const bool first = p1 * p1 + q1 * q1 >= p2 * p2 + q2 * q2;
  pc.d1 = unit(first ? p1 * Xu + q1 * Xv : p2 * Xu + q2 * Xv);
  pc.d2 = gls::cross(n, pc.d1);
  return pc;
}

/// Points of the surface around (u0, v0) with exact normals, as a scanner samples it: one point jittered within each
/// cell of a grid over the parameter box [u0 - du, u0 + du] x [v0 - dv, v0 + dv], the grid's cells of about
/// 1 / `density` area on the surface at (u0, v0), with their parameters; each moved along its normal by a normal
/// deviate of standard deviation `noise` (length) when it is positive.
struct Patch
{
  Cloud cloud;
  std::vector<double> u, v;
};

inline Patch samplePatch(const Surface& s, double u0, double v0, double du, double dv, double density, unsigned seed,
  double noise = 0.0)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(0.0, 1.0);
  std::normal_distribution<double> offset(0.0, noise > 0.0 ? noise : 1.0);
  const double h = 1e-6;
  const double lu = std::sqrt(gls::squaredNorm((0.5 / h) * (s.X(u0 + h, v0) - s.X(u0 - h, v0))));
  const double lv = std::sqrt(gls::squaredNorm((0.5 / h) * (s.X(u0, v0 + h) - s.X(u0, v0 - h))));
  const double spacing = 1.0 / std::sqrt(density); // on the surface
  const int nu = static_cast<int>(std::ceil(2.0 * du * lu / spacing));
  const int nv = static_cast<int>(std::ceil(2.0 * dv * lv / spacing));
  Patch p;
  for (int i = 0; i < nu; ++i)
  {
    for (int j = 0; j < nv; ++j)
    {
      const double u = u0 - du + 2.0 * du * (i + jitter(rng)) / nu;
      const double v = v0 - dv + 2.0 * dv * (j + jitter(rng)) / nv;
      const gls::Vec3 n = s.normal(u, v), x = s.X(u, v) + (noise > 0.0 ? offset(rng) : 0.0) * n;
      p.cloud.points.insert(p.cloud.points.end(), { x.x, x.y, x.z });
      p.cloud.normals.insert(p.cloud.normals.end(), { n.x, n.y, n.z });
      p.u.push_back(u);
      p.v.push_back(v);
    }
  }
  return p;
}

inline double angleDegrees(const gls::Vec3& a, const gls::Vec3& b)
{
  const double c = std::min(1.0, std::abs(gls::dot(a, b)));
  return std::acos(c) * 180.0 / kPi;
}

inline Surface sphere(double R)
{
  return { "sphere",
    [R](double u, double v) {
      return gls::Vec3{ R * std::cos(u) * std::cos(v), R * std::sin(u) * std::cos(v), R * std::sin(v) };
    },
    [](double u, double v) { return gls::Vec3{ std::cos(u) * std::cos(v), std::sin(u) * std::cos(v), std::sin(v) }; } };
}

inline Surface cylinder(double r)
{
  return { "cylinder", [r](double u, double v) { return gls::Vec3{ r * std::cos(u), r * std::sin(u), v }; },
    [](double u, double) { return gls::Vec3{ std::cos(u), std::sin(u), 0.0 }; } };
}

inline Surface torus(double R, double r)
{
  return { "torus",
    [R, r](double u, double v) {
      return gls::Vec3{ (R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v) };
    },
    [](double u, double v) { return gls::Vec3{ std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v) }; } };
}

inline Surface ellipsoid(double a, double b, double c)
{
  return { "ellipsoid",
    [a, b, c](double u, double v) {
      return gls::Vec3{ a * std::cos(v) * std::cos(u), b * std::cos(v) * std::sin(u), c * std::sin(v) };
    },
    [a, b, c](double u, double v) {
      const gls::Vec3 x{ a * std::cos(v) * std::cos(u), b * std::cos(v) * std::sin(u), c * std::sin(v) };
      return unit(gls::Vec3{ x.x / (a * a), x.y / (b * b), x.z / (c * c) });
    } };
}

inline Surface saddle()
{
  return { "saddle", [](double u, double v) { return gls::Vec3{ u, v, 0.5 * (u * u - v * v) }; },
    [](double u, double v) { return unit(gls::Vec3{ -u, v, 1.0 }); } };
}

/// The errors of estimated principal curvatures against the true ones: both curvatures' relative to max|k_true|, and
/// d1's angle (degrees; 90 where it is NaN) where the true ones differ by a fifth of the larger at least.
struct CurvatureErrors
{
  std::vector<double> curvature, direction;
  /// Adds one estimate; true when its directions were compared.
  bool add(const gls::PrincipalCurvatures& got, const gls::PrincipalCurvatures& want)
  {
    const double largest = std::max(std::abs(want.k1), std::abs(want.k2));
    this->curvature.push_back(std::max(std::abs(got.k1 - want.k1), std::abs(got.k2 - want.k2)) / largest);
    if (!(want.k1 - want.k2 >= 0.2 * largest))
    {
      return false;
    }
    this->direction.push_back(std::isfinite(got.d1.x) ? angleDegrees(got.d1, want.d1) : 90.0);
    return true;
  }
};

/// The 99th percentile (the value below which 99% lie; 0 for none).
inline double percentile99(std::vector<double> v)
{
  if (v.empty())
  {
    return 0.0;
  }
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(0.99 * static_cast<double>(v.size() - 1))];
}

} // namespace glstest
