// Helpers for the filter tests: building vtkPolyData clouds, catching VTK errors, reading arrays.
#pragma once

#include "TestClouds.h"

#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <string>
#include <vector>

namespace glstest
{

/// A vertex cloud with the given points and, when not empty, normals (named "Normals", active).
inline vtkSmartPointer<vtkPolyData> makePolyData(const std::vector<double>& xyz, const std::vector<double>& normals)
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  const vtkIdType n = static_cast<vtkIdType>(xyz.size() / 3);
  pts->SetNumberOfPoints(n);
  vtkNew<vtkCellArray> verts;
  for (vtkIdType i = 0; i < n; ++i)
  {
    pts->SetPoint(i, &xyz[3 * i]);
    verts->InsertNextCell(1, &i);
  }
  pd->SetPoints(pts);
  pd->SetVerts(verts);
  if (!normals.empty())
  {
    vtkNew<vtkDoubleArray> nrm;
    nrm->SetName("Normals");
    nrm->SetNumberOfComponents(3);
    nrm->SetNumberOfTuples(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      nrm->SetTuple(i, &normals[3 * i]);
    }
    pd->GetPointData()->SetNormals(nrm);
  }
  return pd;
}

inline vtkSmartPointer<vtkPolyData> makePolyData(const Cloud& c)
{
  return makePolyData(c.points, c.normals);
}

/// Counts the error (or warning) events of an object and keeps their messages, one after the other.
class ErrorCatcher : public vtkCommand
{
public:
  static ErrorCatcher* New() { return new ErrorCatcher; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    ++this->Count;
    this->Message += data ? static_cast<const char*>(data) : "";
  }
  int Count = 0;
  std::string Message;
};

/// Attaches a catcher to the object's error events.
inline vtkSmartPointer<ErrorCatcher> catchErrors(vtkObject* o)
{
  auto c = vtkSmartPointer<ErrorCatcher>::New();
  o->AddObserver(vtkCommand::ErrorEvent, c);
  return c;
}

/// Attaches a catcher to the object's warning events.
inline vtkSmartPointer<ErrorCatcher> catchWarnings(vtkObject* o)
{
  auto c = vtkSmartPointer<ErrorCatcher>::New();
  o->AddObserver(vtkCommand::WarningEvent, c);
  return c;
}

/// The values of a point array as doubles (tuple-major).
inline std::vector<double> values(vtkDataArray* a)
{
  std::vector<double> v;
  if (!a)
  {
    return v;
  }
  v.resize(static_cast<std::size_t>(a->GetNumberOfTuples() * a->GetNumberOfComponents()));
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < a->GetNumberOfComponents(); ++c)
    {
      v[static_cast<std::size_t>(i * a->GetNumberOfComponents() + c)] = a->GetComponent(i, c);
    }
  }
  return v;
}

inline std::vector<double> pointArray(vtkPolyData* pd, const char* name)
{
  return values(pd->GetPointData()->GetArray(name));
}

inline std::vector<double> fieldArray(vtkPolyData* pd, const char* name)
{
  return values(pd->GetFieldData()->GetArray(name));
}

/// True when both vectors have the same length and every pair is equal or both NaN (bitwise comparison of results).
inline bool identical(const std::vector<double>& a, const std::vector<double>& b)
{
  if (a.size() != b.size())
  {
    return false;
  }
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    if (!(a[i] == b[i] || (a[i] != a[i] && b[i] != b[i])))
    {
      return false;
    }
  }
  return true;
}

/// The bundled bunny scan as a vertex cloud (no normals).
vtkSmartPointer<vtkPolyData> bunnyCloud();

/// The bundled bunny mesh with area-weighted vertex normals from vtkPolyDataNormals, oriented by the file's faces.
vtkSmartPointer<vtkPolyData> bunnyMeshWithNormals();

/// A bundled mesh (an OBJ file of Testing/Data) with its vertex normals, as bunnyMeshWithNormals.
vtkSmartPointer<vtkPolyData> meshWithNormals(const std::string& file);

} // namespace glstest
