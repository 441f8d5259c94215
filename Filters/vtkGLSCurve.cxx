#include "vtkGLSCurve.h"

#include "vtkCellArray.h"
#include "vtkMath.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vtkGLSCurve
{

double Diagonal(const std::vector<double>& points)
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
  return std::sqrt(vtkMath::Distance2BetweenPoints(lo, hi));
}

std::string Extract(vtkPolyData* input, int closedMode, Curve& curve)
{
  curve = Curve();
  const vtkIdType n = input->GetNumberOfPoints();
  vtkCellArray* lines = input->GetLines();
  if (lines && lines->GetNumberOfCells() > 0)
  {
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    lines->GetCellAtId(0, npts, pts);
    curve.Ids.assign(pts, pts + npts);
  }
  else
  {
    for (vtkIdType i = 0; i < n; ++i)
    {
      curve.Ids.push_back(i);
    }
  }
  for (vtkIdType id : curve.Ids)
  {
    if (id < 0 || id >= n)
    {
      return "the first line cell refers to point " + std::to_string(id) + ", out of range (" +
        std::to_string(n) + " points)";
    }
  }
  for (vtkIdType id : curve.Ids)
  {
    double p[3];
    input->GetPoint(id, p);
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])))
    {
      return "curve point " + std::to_string(id) + " has a non-finite coordinate";
    }
    curve.Points.insert(curve.Points.end(), p, p + 3);
  }
  const std::size_t m = curve.Ids.size();
  const bool repeated = m >= 2 && curve.Ids.front() == curve.Ids.back();
  bool coincident = false;
  if (m >= 2)
  {
    const double* first = &curve.Points[0];
    const double* last = &curve.Points[3 * (m - 1)];
    const double diagonal = Diagonal(curve.Points);
    coincident = diagonal > 0.0 && std::sqrt(vtkMath::Distance2BetweenPoints(first, last)) <= 1e-9 * diagonal;
  }
  const bool closed = closedMode == 2 || (closedMode == 0 && (repeated || coincident));
  if (repeated || (closed && coincident))
  {
    curve.Ids.pop_back();
    curve.Points.resize(curve.Points.size() - 3);
  }
  curve.Closed = closed;
  if (curve.Ids.size() < 3)
  {
    return "the curve has " + std::to_string(curve.Ids.size()) +
      " distinct points; at least 3 are needed (the first line cell's points, or all points when there is no "
      "line cell; join separate segments with vtkStripper)";
  }
  return "";
}

Plane FitPlane(const std::vector<double>& points)
{
  Plane plane;
  const std::size_t n = points.size() / 3;
  for (int a = 0; a < 3; ++a)
  {
    plane.Center[a] = 0.0;
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      plane.Center[a] += points[3 * i + a] / static_cast<double>(n);
    }
  }
  double cov[3][3] = { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } };
  for (std::size_t i = 0; i < n; ++i)
  {
    double d[3];
    for (int a = 0; a < 3; ++a)
    {
      d[a] = points[3 * i + a] - plane.Center[a];
    }
    for (int a = 0; a < 3; ++a)
    {
      for (int b = 0; b < 3; ++b)
      {
        cov[a][b] += d[a] * d[b];
      }
    }
  }
  double vectors[3][3], values[3];
  double* a[3] = { cov[0], cov[1], cov[2] };
  double* v[3] = { vectors[0], vectors[1], vectors[2] };
  vtkMath::Jacobi(a, values, v); // decreasing eigenvalues, eigenvectors in columns
  int largest = 0;
  for (int c = 0; c < 3; ++c)
  {
    plane.E1[c] = vectors[c][0];
    plane.Normal[c] = vectors[c][2];
    if (std::abs(plane.Normal[c]) > std::abs(plane.Normal[largest]))
    {
      largest = c;
    }
  }
  if (plane.Normal[largest] < 0.0)
  {
    for (int c = 0; c < 3; ++c)
    {
      plane.Normal[c] = -plane.Normal[c];
    }
  }
  vtkMath::Cross(plane.Normal, plane.E1, plane.E2);
  for (std::size_t i = 0; i < n; ++i)
  {
    double local[3];
    ToPlane(plane, &points[3 * i], local, true);
    plane.MaxDistance = std::max(plane.MaxDistance, std::abs(local[2]));
  }
  return plane;
}

void ToPlane(const Plane& plane, const double* in, double* out, bool isPoint)
{
  double d[3];
  for (int a = 0; a < 3; ++a)
  {
    d[a] = isPoint ? in[a] - plane.Center[a] : in[a];
  }
  out[0] = vtkMath::Dot(d, plane.E1);
  out[1] = vtkMath::Dot(d, plane.E2);
  out[2] = vtkMath::Dot(d, plane.Normal);
}

std::vector<double> InPlaneNormals(const std::vector<double>& points, bool closed)
{
  const std::size_t n = points.size() / 3;
  std::vector<double> normals(3 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::size_t prev = closed ? (i + n - 1) % n : (i == 0 ? 0 : i - 1);
    const std::size_t next = closed ? (i + 1) % n : std::min(i + 1, n - 1);
    const double tx = points[3 * next] - points[3 * prev];
    const double ty = points[3 * next + 1] - points[3 * prev + 1];
    const double len = std::hypot(tx, ty);
    const double nan = std::numeric_limits<double>::quiet_NaN();
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

std::vector<double> Arclengths(const std::vector<double>& points, bool closed)
{
  const std::size_t n = points.size() / 3;
  std::vector<double> s(1, 0.0);
  for (std::size_t i = 1; i < n + (closed ? 1 : 0); ++i)
  {
    const double* a = &points[3 * (i - 1)];
    const double* b = &points[3 * (i % n)];
    s.push_back(s.back() + std::sqrt(vtkMath::Distance2BetweenPoints(a, b)));
  }
  return s;
}

}
