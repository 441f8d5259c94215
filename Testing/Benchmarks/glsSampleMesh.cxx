// Writes a bundled mesh sampled uniformly by area as a point cloud in a binary float PLY with positions only (no
// normals, no faces): the input of the main-job benchmarks M1-M3 (docs/performance.md, "The main job at scale").
//   glsSampleMesh MODEL POINTS OUTPUT.ply [SEED (1)]      MODEL: a path, or a bundled name (bunny, rocker-arm, ...)
#include "MeshSampler.h"

#include "vtkNew.h"
#include "vtkPLYWriter.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char* argv[])
{
  if (argc < 4)
  {
    std::fprintf(stderr, "usage: %s MODEL POINTS OUTPUT.ply [SEED]\n", argv[0]);
    return 2;
  }
  std::string model = argv[1];
  if (model.find('/') == std::string::npos)
  {
    model = std::string(GLS_BENCHMARK_DATA_DIR) + "/" + (model == "bunny" ? "stanford-bunny" : model) + ".obj";
  }
  const long long count = std::atoll(argv[2]);
  const unsigned long long seed = argc > 4 ? std::strtoull(argv[4], nullptr, 10) : 1;
  if (count < 1)
  {
    std::fprintf(stderr, "POINTS must be positive\n");
    return 2;
  }
  vtkSmartPointer<vtkPolyData> cloud = sampleMeshSurface(model, count, seed);
  if (!cloud)
  {
    std::fprintf(stderr, "cannot read %s\n", model.c_str());
    return 2;
  }
  vtkNew<vtkPolyData> positions; // positions only: a scan as a user brings it
  positions->SetPoints(cloud->GetPoints());
  vtkNew<vtkPLYWriter> writer;
  writer->SetFileName(argv[3]);
  writer->SetInputData(positions);
  writer->SetFileTypeToBinary();
  if (writer->Write() != 1)
  {
    std::fprintf(stderr, "cannot write %s\n", argv[3]);
    return 2;
  }
  std::printf("wrote %s: %lld points of %s\n", argv[3], count, model.c_str());
  return 0;
}
