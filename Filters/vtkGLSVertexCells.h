// One vertex cell per point, for the readers' point clouds (private to the module).
#ifndef vtkGLSVertexCells_h
#define vtkGLSVertexCells_h

#include "vtkCellArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include <numeric>

/// The cells 0, 1, ..., n - 1, each one vertex.
inline vtkSmartPointer<vtkCellArray> vtkGLSVertexCells(vtkIdType n)
{
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfTuples(n + 1);
  connectivity->SetNumberOfTuples(n);
  std::iota(offsets->GetPointer(0), offsets->GetPointer(0) + n + 1, vtkIdType(0));
  std::iota(connectivity->GetPointer(0), connectivity->GetPointer(0) + n, vtkIdType(0));
  auto verts = vtkSmartPointer<vtkCellArray>::New();
  verts->SetData(offsets, connectivity);
  return verts;
}

#endif
