#include "gls/Planarity.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace gls
{
namespace
{
bool finite3(const double* p)
{
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}
}

PlaneZ commonZ(const double* xyz, std::size_t n)
{
  PlaneZ verdict;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double* p = xyz + 3 * i;
    if (!finite3(p))
    {
      continue;
    }
    if (!verdict.any)
    {
      verdict.any = verdict.planar = true;
      verdict.z = p[2];
    }
    else if (p[2] != verdict.z)
    {
      verdict.planar = false;
      return verdict;
    }
  }
  return verdict;
}

PlaneZ twoDimensionalFitInput(const double* xyz, const double* normals, std::size_t n)
{
  PlaneZ verdict;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double* m = normals + 3 * i;
    const double len2 = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];
    if (!finite3(xyz + 3 * i) || !(len2 > 0.0 && std::isfinite(len2)))
    {
      continue; // left out of every fit
    }
    if (!verdict.any)
    {
      verdict.any = verdict.planar = true;
      verdict.z = xyz[3 * i + 2];
    }
    if (m[2] != 0.0 || xyz[3 * i + 2] != verdict.z)
    {
      verdict.planar = false;
      return verdict;
    }
  }
  return verdict;
}

PlaneFit fitPlane(const double* xyz, std::size_t n)
{
  PlaneFit plane;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i)
  {
    center += Eigen::Vector3d(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]) / static_cast<double>(n);
  }
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < n; ++i)
  {
    const Eigen::Vector3d d = Eigen::Vector3d(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]) - center;
    cov += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov); // ascending eigenvalues
  Eigen::Vector3d normal = solver.eigenvectors().col(0);
  const Eigen::Vector3d e1 = solver.eigenvectors().col(2);
  int largest = 0;
  for (int c = 1; c < 3; ++c)
  {
    largest = std::abs(normal[c]) > std::abs(normal[largest]) ? c : largest;
  }
  if (normal[largest] < 0.0)
  {
    normal = -normal;
  }
  const Eigen::Vector3d e2 = normal.cross(e1);
  for (int c = 0; c < 3; ++c)
  {
    plane.center[c] = center[c];
    plane.e1[c] = e1[c];
    plane.e2[c] = e2[c];
    plane.normal[c] = normal[c];
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    double local[3];
    toPlaneFrame(plane, xyz + 3 * i, local, true);
    plane.maxDistance = std::max(plane.maxDistance, std::abs(local[2]));
  }
  return plane;
}

void toPlaneFrame(const PlaneFit& plane, const double* in, double* out, bool isPoint)
{
  double d[3];
  for (int a = 0; a < 3; ++a)
  {
    d[a] = isPoint ? in[a] - plane.center[a] : in[a];
  }
  out[0] = d[0] * plane.e1[0] + d[1] * plane.e1[1] + d[2] * plane.e1[2];
  out[1] = d[0] * plane.e2[0] + d[1] * plane.e2[1] + d[2] * plane.e2[2];
  out[2] = d[0] * plane.normal[0] + d[1] * plane.normal[1] + d[2] * plane.normal[2];
}

} // namespace gls
