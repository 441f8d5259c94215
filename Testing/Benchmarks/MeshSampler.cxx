#include "MeshSampler.h"

#include "TestClouds.h"

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

  // The mesh's points, unit vertex normals and triangles, for the one sampler (TestClouds.h).
  std::vector<double> xyz(3 * static_cast<std::size_t>(mesh->GetNumberOfPoints()));
  std::vector<double> vertexNormals(xyz.size());
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    mesh->GetPoint(i, &xyz[3 * static_cast<std::size_t>(i)]);
    vn->GetTuple(i, &vertexNormals[3 * static_cast<std::size_t>(i)]);
  }
  std::vector<std::array<std::size_t, 3>> tris;
  vtkCellArray* polys = mesh->GetPolys();
  polys->InitTraversal();
  vtkNew<vtkIdList> ids;
  while (polys->GetNextCell(ids))
  {
    if (ids->GetNumberOfIds() == 3)
    {
      tris.push_back({ static_cast<std::size_t>(ids->GetId(0)), static_cast<std::size_t>(ids->GetId(1)),
        static_cast<std::size_t>(ids->GetId(2)) });
    }
  }
  if (tris.empty())
  {
    return nullptr;
  }

  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(count);
  vtkNew<vtkDoubleArray> out;
  out->SetName("Normals");
  out->SetNumberOfComponents(3);
  out->SetNumberOfTuples(count);
  glstest::sampleTrianglesByArea(xyz, vertexNormals, tris, static_cast<std::size_t>(count), seed,
    coordinates->GetPointer(0), out->GetPointer(0));
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  vtkNew<vtkCellArray> verts;
  for (vtkIdType i = 0; i < count; ++i)
  {
    verts->InsertNextCell(1, &i);
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  cloud->SetVerts(verts);
  cloud->GetPointData()->SetNormals(out);
  return cloud;
}
