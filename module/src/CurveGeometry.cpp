#include "gls/CurveGeometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gls
{
namespace
{
double distance(const double* a, const double* b)
{
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}
}

double boundingDiagonal(const std::vector<double>& points)
{
  if (points.empty())
  {
    return 0.0;
  }
  double lo[3] = { points[0], points[1], points[2] }, hi[3] = { points[0], points[1], points[2] };
  for (std::size_t i = 0; i < points.size(); i += 3)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], points[i + a]);
      hi[a] = std::max(hi[a], points[i + a]);
    }
  }
  return distance(lo, hi);
}

std::vector<double> curveArclengths(const std::vector<double>& points, bool closed)
{
  const std::size_t n = points.size() / 3;
  std::vector<double> s(1, 0.0);
  for (std::size_t i = 1; i < n + (closed ? 1 : 0); ++i)
  {
    s.push_back(s.back() + distance(&points[3 * (i - 1)], &points[3 * (i % n)]));
  }
  return s;
}

std::vector<double> inPlaneCurveNormals(const std::vector<double>& points, bool closed)
{
  const std::size_t n = points.size() / 3;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> normals(3 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::size_t prev = closed ? (i + n - 1) % n : (i == 0 ? 0 : i - 1);
    const std::size_t next = closed ? (i + 1) % n : std::min(i + 1, n - 1);
    const double tx = points[3 * next] - points[3 * prev];
    const double ty = points[3 * next + 1] - points[3 * prev + 1];
    const double len = std::hypot(tx, ty);
    normals[3 * i] = len > 0.0 ? -ty / len : nan; // left of the tangent, +z up
    normals[3 * i + 1] = len > 0.0 ? tx / len : nan;
  }
  if (closed)
  {
    double twiceArea = 0.0; // shoelace: > 0 for a counter-clockwise curve, whose left normals point inward
    for (std::size_t i = 0; i < n; ++i)
    {
      const std::size_t j = (i + 1) % n;
      twiceArea += points[3 * i] * points[3 * j + 1] - points[3 * j] * points[3 * i + 1];
    }
    if (twiceArea > 0.0)
    {
      for (std::size_t i = 0; i < n; ++i)
      {
        normals[3 * i] = -normals[3 * i];
        normals[3 * i + 1] = -normals[3 * i + 1];
      }
    }
  }
  return normals;
}

} // namespace gls
