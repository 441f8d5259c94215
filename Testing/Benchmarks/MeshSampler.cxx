#include "MeshSampler.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

vtkSmartPointer<vtkPolyData> sampleMeshSurface(const std::string& path, std::int64_t count, std::uint64_t seed)
{
  vtkSmartPointer<vtkAlgorithm> reader;
  if (path.size() > 4 && path.substr(path.size() - 4) == ".ply")
  {
    auto r = vtkSmartPointer<vtkPLYReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else
  {
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(reader->GetOutputPort());
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(triangles->GetOutputPort());
  normals->SplittingOff();
  normals->ConsistencyOff();
  normals->ComputePointNormalsOn();
  normals->Update();
  vtkPolyData* mesh = normals->GetOutput();
  vtkDataArray* vn = mesh->GetPointData()->GetNormals();
  if (!vn || mesh->GetNumberOfPolys() == 0)
  {
    return nullptr;
  }

  // Cumulative triangle areas.
  std::vector<std::array<vtkIdType, 3>> tris;
  std::vector<double> cumulative;
  double total = 0.0;
  vtkCellArray* polys = mesh->GetPolys();
  polys->InitTraversal();
  vtkNew<vtkIdList> ids;
  while (polys->GetNextCell(ids))
  {
    if (ids->GetNumberOfIds() != 3)
    {
      continue;
    }
    double a[3], b[3], c[3];
    mesh->GetPoint(ids->GetId(0), a);
    mesh->GetPoint(ids->GetId(1), b);
    mesh->GetPoint(ids->GetId(2), c);
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
    total += 0.5 * std::sqrt(x * x + y * y + z * z);
    cumulative.push_back(total);
    tris.push_back({ ids->GetId(0), ids->GetId(1), ids->GetId(2) });
  }

  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(count);
  vtkNew<vtkDoubleArray> out;
  out->SetName("Normals");
  out->SetNumberOfComponents(3);
  out->SetNumberOfTuples(count);
  vtkNew<vtkCellArray> verts;
  for (vtkIdType i = 0; i < count; ++i)
  {
    const double r = uniform(rng) * total;
    const std::size_t t = std::min<std::size_t>(
      static_cast<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), r) - cumulative.begin()),
      tris.size() - 1);
    double s = uniform(rng), w = uniform(rng);
    if (s + w > 1.0)
    {
      s = 1.0 - s;
      w = 1.0 - w;
    }
    const double bary[3] = { 1.0 - s - w, s, w };
    double p[3] = { 0, 0, 0 }, n[3] = { 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
    {
      double q[3], m[3];
      mesh->GetPoint(tris[t][k], q);
      vn->GetTuple(tris[t][k], m);
      for (int a = 0; a < 3; ++a)
      {
        p[a] += bary[k] * q[a];
        n[a] += bary[k] * m[a];
      }
    }
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& c : n)
    {
      c /= len;
    }
    points->SetPoint(i, p);
    out->SetTuple(i, n);
    verts->InsertNextCell(1, &i);
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  cloud->SetVerts(verts);
  cloud->GetPointData()->SetNormals(out);
  return cloud;
}
