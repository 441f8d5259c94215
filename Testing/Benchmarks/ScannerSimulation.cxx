#include "ScannerSimulation.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFeatureEdges.h"
#include "vtkMath.h"
#include "vtkIdList.h"
#include "vtkCellLocator.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkStaticPointLocator.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace
{

constexpr double kPi = 3.14159265358979323846;

double wrapAngle(double a)
{
  while (a > kPi)
  {
    a -= 2 * kPi;
  }
  while (a < -kPi)
  {
    a += 2 * kPi;
  }
  return a;
}

vtkSmartPointer<vtkPolyData> trianglesWithCellNormals(vtkPolyData* mesh)
{
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(mesh);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(triangles->GetOutputPort());
  normals->ComputeCellNormalsOn();
  normals->ComputePointNormalsOn();
  normals->SplittingOff();
  normals->ConsistencyOff(); // the file's own orientation
  normals->AutoOrientNormalsOff();
  normals->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(normals->GetOutput());
  return out;
}

} // namespace

ScannerScan simulateScanner(vtkPolyData* mesh, const ScannerSettings& settings)
{
  ScannerScan scan;
  vtkSmartPointer<vtkPolyData> tri = trianglesWithCellNormals(mesh);
  vtkDataArray* cellNormals = tri->GetCellData()->GetNormals();
  vtkDataArray* pointNormals = tri->GetPointData()->GetNormals();
  vtkNew<vtkIdList> corners;
  if (tri->GetNumberOfCells() == 0 || !cellNormals)
  {
    return scan;
  }
  vtkNew<vtkCellLocator> tree;
  tree->SetNumberOfCellsPerNode(8);
  tree->SetDataSet(tri);
  tree->BuildLocator();

  double b[6];
  tri->GetBounds(b);
  const double centre[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  const double diagonal = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
    (b[5] - b[4]) * (b[5] - b[4]));
  std::vector<std::array<double, 3>> positions = settings.Positions;
  if (positions.empty())
  {
    for (double azimuth : { 0.3, 0.3 + 110.0 * kPi / 180.0 })
    {
      const double elevation = 20.0 * kPi / 180.0, d = 2.5 * diagonal;
      positions.push_back({ centre[0] + d * std::cos(elevation) * std::cos(azimuth),
        centre[1] + d * std::cos(elevation) * std::sin(azimuth), centre[2] + d * std::sin(elevation) });
    }
  }

  for (const auto& p : positions)
  {
    // The angular box of the bounding box seen from p (azimuth relative to the centre's direction).
    const double toCentre[3] = { centre[0] - p[0], centre[1] - p[1], centre[2] - p[2] };
    const double azimuth0 = std::atan2(toCentre[1], toCentre[0]);
    double azMin = 0, azMax = 0, elMin = kPi, elMax = -kPi;
    for (int corner = 0; corner < 8; ++corner)
    {
      const double c[3] = { b[corner & 1] - p[0], b[2 + ((corner >> 1) & 1)] - p[1], b[4 + ((corner >> 2) & 1)] - p[2] };
      const double az = wrapAngle(std::atan2(c[1], c[0]) - azimuth0);
      const double el = std::atan2(c[2], std::hypot(c[0], c[1]));
      azMin = std::min(azMin, az);
      azMax = std::max(azMax, az);
      elMin = std::min(elMin, el);
      elMax = std::max(elMax, el);
    }
    const int along = std::max(settings.SamplesAlong, 2);
    const double stepAlong = (elMax - elMin) / (along - 1);
    const double stepAcross = settings.Anisotropy * stepAlong;
    const int lines = std::max(2, static_cast<int>(std::ceil((azMax - azMin) / stepAcross)) + 1);
    const double reach = std::sqrt(toCentre[0] * toCentre[0] + toCentre[1] * toCentre[1] + toCentre[2] * toCentre[2]) +
      diagonal;
    for (int line = 0; line < lines; ++line)
    {
      const double az = azimuth0 + azMin + line * stepAcross;
      for (int s = 0; s < along; ++s)
      {
        const double el = elMin + s * stepAlong;
        const double d[3] = { std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el) };
        double p0[3] = { p[0], p[1], p[2] };
        double p1[3] = { p[0] + reach * d[0], p[1] + reach * d[1], p[2] + reach * d[2] };
        // The first crossing of the ray (the cell locator walks its buckets along the ray, nearest first).
        double t = 0, x[3], pcoords[3];
        int subId = 0;
        vtkIdType cell = -1;
        if (!tree->IntersectWithLine(p0, p1, 0.0, t, x, pcoords, subId, cell) || cell < 0)
        {
          continue;
        }
        double n[3];
        cellNormals->GetTuple(cell, n);
        scan.WoundNormals.insert(scan.WoundNormals.end(), n, n + 3);
        // The smooth normal: the corners' vertex normals, barycentric weights (1 - r - s, r, s).
        tri->GetCellPoints(cell, corners);
        double smooth[3] = { 0, 0, 0 };
        const double weights[3] = { 1.0 - pcoords[0] - pcoords[1], pcoords[0], pcoords[1] };
        for (int c = 0; c < 3 && corners->GetNumberOfIds() == 3; ++c)
        {
          double v[3];
          pointNormals->GetTuple(corners->GetId(c), v);
          for (int a = 0; a < 3; ++a)
          {
            smooth[a] += weights[c] * v[a];
          }
        }
        const double length = std::sqrt(smooth[0] * smooth[0] + smooth[1] * smooth[1] + smooth[2] * smooth[2]);
        const double turn = smooth[0] * d[0] + smooth[1] * d[1] + smooth[2] * d[2] > 0.0 ? -1.0 : 1.0;
        for (int a = 0; a < 3; ++a)
        {
          smooth[a] = length > 0.0 ? turn * smooth[a] / length : std::nan("");
        }
        scan.SmoothNormals.insert(scan.SmoothNormals.end(), smooth, smooth + 3);
        // The side the ray sees: outward on a closed surface scanned from outside, whatever the file's winding.
        if (n[0] * d[0] + n[1] * d[1] + n[2] * d[2] > 0.0)
        {
          n[0] = -n[0];
          n[1] = -n[1];
          n[2] = -n[2];
          ++scan.FlippedTriangles;
        }
        scan.Points.insert(scan.Points.end(), x, x + 3);
        scan.Normals.insert(scan.Normals.end(), n, n + 3);
        scan.Viewpoints.insert(scan.Viewpoints.end(), p.begin(), p.end());
        scan.Cells.push_back(static_cast<long long>(cell));
      }
    }
  }
  return scan;
}

vtkSmartPointer<vtkPolyData> scanAsPolyData(const ScannerScan& scan)
{
  const vtkIdType n = static_cast<vtkIdType>(scan.Size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkNew<vtkDoubleArray> normals, viewpoints;
  normals->SetName("TrueNormals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(n);
  viewpoints->SetName("ScannerPosition");
  viewpoints->SetNumberOfComponents(3);
  viewpoints->SetNumberOfTuples(n);
  vtkNew<vtkCellArray> verts;
  for (vtkIdType i = 0; i < n; ++i)
  {
    points->SetPoint(i, &scan.Points[3 * i]);
    normals->SetTuple(i, &scan.Normals[3 * i]);
    viewpoints->SetTuple(i, &scan.Viewpoints[3 * i]);
    verts->InsertNextCell(1, &i);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetVerts(verts);
  pd->GetPointData()->AddArray(normals);
  pd->GetPointData()->AddArray(viewpoints);
  return pd;
}

std::vector<double> distanceToCreases(vtkPolyData* mesh, const ScannerScan& scan, double featureAngle)
{
  std::vector<double> distance(scan.Size(), std::numeric_limits<double>::infinity());
  vtkSmartPointer<vtkPolyData> tri = trianglesWithCellNormals(mesh);
  vtkNew<vtkFeatureEdges> edges;
  edges->SetInputData(tri);
  edges->FeatureEdgesOn();
  edges->BoundaryEdgesOff();
  edges->NonManifoldEdgesOff();
  edges->ManifoldEdgesOff();
  edges->SetFeatureAngle(featureAngle);
  edges->Update();
  vtkPolyData* creases = edges->GetOutput();
  if (creases->GetNumberOfCells() == 0)
  {
    return distance;
  }
  // The crease lines sampled at 1/4000 of the diagonal, then the nearest sample of every scan point.
  const double spacing = tri->GetLength() / 4000.0;
  vtkNew<vtkPoints> samples;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < creases->GetNumberOfCells(); ++c)
  {
    creases->GetCellPoints(c, ids);
    for (vtkIdType k = 0; k + 1 < ids->GetNumberOfIds(); ++k)
    {
      double a[3], e[3];
      creases->GetPoint(ids->GetId(k), a);
      creases->GetPoint(ids->GetId(k + 1), e);
      const double length = std::sqrt(vtkMath::Distance2BetweenPoints(a, e));
      const int steps = std::max(1, static_cast<int>(std::ceil(length / spacing)));
      for (int s = 0; s <= steps; ++s)
      {
        const double f = static_cast<double>(s) / steps;
        samples->InsertNextPoint(a[0] + f * (e[0] - a[0]), a[1] + f * (e[1] - a[1]), a[2] + f * (e[2] - a[2]));
      }
    }
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(samples);
  vtkNew<vtkStaticPointLocator> locator;
  locator->SetDataSet(cloud);
  locator->BuildLocator();
  for (std::size_t i = 0; i < scan.Size(); ++i)
  {
    const double* x = &scan.Points[3 * i];
    const vtkIdType nearest = locator->FindClosestPoint(x);
    double y[3];
    samples->GetPoint(nearest, y);
    distance[i] = std::sqrt(vtkMath::Distance2BetweenPoints(x, y));
  }
  return distance;
}
