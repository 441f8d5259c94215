#include "vtkGLSPlyWriter.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSReaderParts.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include "gls/PlyWriter.h"

#include <fstream>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkGLSPlyWriter);

vtkGLSPlyWriter::vtkGLSPlyWriter() = default;

vtkGLSPlyWriter::~vtkGLSPlyWriter() = default;

void vtkGLSPlyWriter::WriteData()
{
  std::vector<double> xyz;
  vtkPointSet* input = this->InputPositions(xyz);
  if (!input)
  {
    return;
  }
  const vtkIdType n = input->GetNumberOfPoints();
  gls::PlyWriteSource source;
  source.n = static_cast<std::size_t>(n);
  source.xyz = xyz.data();
  source.floatPositions = input->GetPoints()->GetDataType() == VTK_FLOAT;
  vtkPointData* pd = input->GetPointData();
  std::vector<std::shared_ptr<void>> kept;
  vtkDataArray* normals = pd->GetArray(vtkGLSArrayNames::Normals);
  const bool hasNormals = normals && normals->GetNumberOfComponents() == 3 && normals->GetNumberOfTuples() == n;
  if (hasNormals)
  {
    source.normals = vtkGLSValuesAs<float>(normals, 1.0, kept);
  }
  vtkDataArray* colours = pd->GetArray(vtkGLSArrayNames::Colors);
  const bool hasColours = colours && colours->GetNumberOfComponents() == 3 && colours->GetNumberOfTuples() == n;
  if (hasColours)
  {
    // 16-bit colours (a LAS file's) as PLY's bytes.
    source.colours = vtkGLSValuesAs<std::uint8_t>(
      colours, colours->GetDataType() == VTK_UNSIGNED_SHORT ? 1.0 / 257.0 : 1.0, kept);
  }
  for (int k = 0; k < pd->GetNumberOfArrays(); ++k)
  {
    vtkDataArray* a = pd->GetArray(k);
    if (!a || !a->GetName() || a->GetNumberOfTuples() != n || (hasNormals && a == normals) ||
      (hasColours && a == colours))
    {
      continue;
    }
    gls::PlyScalarSource scalar;
    scalar.name = a->GetName();
    scalar.components = a->GetNumberOfComponents();
    PerPointValues(a, scalar.floats, scalar.doubles, kept);
    source.scalars.push_back(scalar);
  }
  if (auto* mesh = vtkPolyData::SafeDownCast(input))
  {
    source.faceOffsets.push_back(0);
    auto polys = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
    for (polys->GoToFirstCell(); !polys->IsDoneWithTraversal(); polys->GoToNextCell())
    {
      vtkIdType size = 0;
      const vtkIdType* ids = nullptr;
      polys->GetCurrentCell(size, ids);
      source.faceIndices.insert(source.faceIndices.end(), ids, ids + size);
      source.faceOffsets.push_back(static_cast<std::int64_t>(source.faceIndices.size()));
    }
  }
  source.comments.push_back("written by GrowingLeastSquares (vtkGLSPlyWriter)");
  auto* wkt = vtkStringArray::SafeDownCast(input->GetFieldData()->GetAbstractArray(vtkGLSArrayNames::CoordinateSystemWKT));
  if (wkt && wkt->GetNumberOfValues() > 0)
  {
    source.comments.push_back("coordinate system: " + wkt->GetValue(0));
  }
  gls::PlyWriteResult result;
  if (!this->WriteStream("PLY", [&](std::ostream& out, std::string& error) {
        return gls::writePly(out, source, result, error);
      }))
  {
    return;
  }
  this->WarnPointsLeftOut(
    result.leftOut, source.n, std::to_string(result.facesLeftOut) + " faces with them");
  std::ostringstream d;
  d << "binary PLY, " << result.written << " vertices (" << (source.floatPositions ? "float" : "double") << ")";
  if (result.leftOut > 0)
  {
    d << " (" << result.leftOut << " with a non-finite coordinate left out)";
  }
  d << ", " << source.scalars.size() << " scalar arrays, " << result.faces << " faces";
  this->Description = d.str();
}
