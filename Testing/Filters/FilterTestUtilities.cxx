#include "FilterTestUtilities.h"

#include "vtkOBJReader.h"
#include "vtkPolyDataNormals.h"

namespace glstest
{

vtkSmartPointer<vtkPolyData> bunnyCloud()
{
  const std::vector<double> xyz = readObjVertices(dataFile("stanford-bunny.obj"));
  return makePolyData(xyz, {});
}

vtkSmartPointer<vtkPolyData> bunnyMeshWithNormals()
{
  return meshWithNormals("stanford-bunny.obj");
}

vtkSmartPointer<vtkPolyData> meshWithNormals(const std::string& file)
{
  vtkNew<vtkOBJReader> reader;
  reader->SetFileName(dataFile(file).c_str());
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(reader->GetOutputPort());
  normals->SplittingOff();
  normals->ConsistencyOff(); // the file's own face orientation (ConsistencyOn flips about 3% of this mesh)
  normals->AutoOrientNormalsOff();
  normals->ComputePointNormalsOn();
  normals->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(normals->GetOutput());
  return out;
}

} // namespace glstest
