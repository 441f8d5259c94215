// What the readers share (private to the module): one vertex cell per point, a file name's extension.
#ifndef vtkGLSReaderParts_h
#define vtkGLSReaderParts_h

#include "vtkCellArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cctype>
#include <numeric>
#include <string>

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

/// The extension of a file name, lower case, without its dot ("" when there is none).
inline std::string vtkGLSFileExtension(const char* name)
{
  const std::string path = name ? name : "";
  const auto dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

#endif
