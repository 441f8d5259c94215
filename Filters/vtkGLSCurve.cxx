#include "vtkGLSCurve.h"

#include "vtkCellArray.h"
#include "vtkMath.h"
#include "vtkPolyData.h"

#include "gls/CurveGeometry.h"

#include <cmath>

namespace vtkGLSCurve
{

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
    const double diagonal = gls::boundingDiagonal(curve.Points);
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

}
