// The GLS pipeline from C++, as a user's program writes it: reads a point cloud or mesh, estimates oriented normals
// unless the file has them, then the scale space (20 quadratic scales from 0.8% to 8% of the bounding-box diagonal,
// the filters' defaults), the geometric variation, the continuous features and the multi-scale dissimilarity to one
// query point, and writes every array to a .vtp file.
//
//   glsExample <input: .obj .ply .vtp .xyz .pts .csv .txt> [output.vtp = gls-example.vtp] [query point id = 0]
//
// Exit status: 0 on success, 1 when the input cannot be read or a filter fails (its error is printed), 2 on bad
// arguments.
#include "vtkGLSContinuousFeatures.h"
#include "vtkGLSGeometricVariation.h"
#include "vtkGLSMultiScaleDissimilarity.h"
#include "vtkGLSNormalEstimation.h"
#include "vtkGLSPointCloudReader.h"
#include "vtkGLSScaleSpace.h"

#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{

/// A reader for the file's extension (lower-cased), or null for an unsupported one.
vtkSmartPointer<vtkAlgorithm> readerFor(const std::string& path)
{
  std::string ext = path.substr(std::min(path.size(), path.find_last_of('.') + 1));
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == "obj")
  {
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (ext == "ply")
  {
    auto r = vtkSmartPointer<vtkPLYReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (ext == "vtp")
  {
    auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (ext == "xyz" || ext == "pts" || ext == "csv" || ext == "txt")
  {
    auto r = vtkSmartPointer<vtkGLSPointCloudReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  return nullptr;
}

} // namespace

int main(int argc, char* argv[])
{
  if (argc < 2 || argc > 4)
  {
    std::fprintf(stderr, "usage: %s <input: .obj .ply .vtp .xyz .pts .csv .txt> [output.vtp] [query point id]\n",
      argv[0]);
    return 2;
  }
  const std::string output = argc > 2 ? argv[2] : "gls-example.vtp";
  const vtkIdType query = argc > 3 ? std::atoll(argv[3]) : 0;

  auto reader = readerFor(argv[1]);
  if (!reader)
  {
    std::fprintf(stderr, "error: %s: unsupported file type\n", argv[1]);
    return 2;
  }
  reader->Update();
  vtkPolyData* input = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!input || input->GetNumberOfPoints() == 0)
  {
    std::fprintf(stderr, "error: %s: no points read\n", argv[1]);
    return 1;
  }

  // Normals: the file's, else PCA over the 16 nearest neighbours, oriented by a minimum spanning tree.
  vtkNew<vtkGLSNormalEstimation> normals;
  normals->SetInputConnection(reader->GetOutputPort());
  vtkNew<vtkGLSScaleSpace> scaleSpace; // defaults: 20 quadratic scales, 0.8% to 8% of the diagonal
  const bool hasNormals = input->GetPointData()->GetNormals() != nullptr;
  scaleSpace->SetInputConnection(hasNormals ? reader->GetOutputPort() : normals->GetOutputPort());
  vtkNew<vtkGLSGeometricVariation> variation; // nu per scale, from the stored scale space
  variation->SetInputConnection(scaleSpace->GetOutputPort());
  vtkNew<vtkGLSContinuousFeatures> features; // f in [0, 1]
  features->SetInputConnection(variation->GetOutputPort());
  vtkNew<vtkGLSMultiScaleDissimilarity> dissimilarity; // Delta(p, query) over all scales
  dissimilarity->SetInputConnection(features->GetOutputPort());
  dissimilarity->SetQueryPointId(query);
  dissimilarity->Update();

  vtkPolyData* result = dissimilarity->GetPolyDataOutput(); // the output has the input's type
  vtkDataArray* f = result->GetPointData()->GetArray("GLSFeature");
  vtkDataArray* delta = result->GetPointData()->GetArray("GLSDissimilarity");
  if (!f || !delta)
  {
    std::fprintf(stderr, "error: the pipeline failed (see the messages above)\n");
    return 1;
  }
  double fRange[2], deltaRange[2];
  f->GetRange(fRange);
  delta->GetRange(deltaRange);
  std::printf("%lld points; GLSFeature in [%g, %g]; GLSDissimilarity to point %lld in [%g, %g]\n",
    static_cast<long long>(result->GetNumberOfPoints()), fRange[0], fRange[1], static_cast<long long>(query),
    deltaRange[0], deltaRange[1]);

  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetFileName(output.c_str());
  writer->SetInputData(result);
  writer->SetDataModeToBinary(); // inline binary: ParaView 5.11 misreads some appended files with many components
  if (writer->Write() != 1)
  {
    std::fprintf(stderr, "error: cannot write %s\n", output.c_str());
    return 1;
  }
  std::printf("wrote %s\n", output.c_str());
  return 0;
}
