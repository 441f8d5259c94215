// The GLS pipeline in C++ (the pvpython main job gls-analyze is the full one, with pictures): reads a point cloud
// or mesh (OBJ, PLY, VTP), estimates oriented normals unless the file has them, runs the GLS scale space (20
// quadratic scales from 0.8% to 8% of the bounding-box diagonal), the geometric variation and the continuous
// features, and writes a .vtp with every array.
//
//   glsAnalyze [input = bundled bunny] [output.vtp = gls-result.vtp]
#include "vtkGLSContinuousFeatures.h"
#include "vtkGLSGeometricVariation.h"
#include "vtkGLSNormalEstimation.h"
#include "vtkGLSScaleSpace.h"

#include "vtkCallbackCommand.h"
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
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

namespace
{

std::string lowerExtension(const std::string& path)
{
  const auto dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

vtkSmartPointer<vtkPolyData> readCloud(const std::string& path)
{
  if (!std::ifstream(path))
  {
    std::fprintf(stderr, "error: cannot open '%s'\n", path.c_str());
    return nullptr;
  }
  const std::string ext = lowerExtension(path);
  vtkSmartPointer<vtkAlgorithm> reader;
  if (ext == "obj")
  {
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (ext == "ply")
  {
    auto r = vtkSmartPointer<vtkPLYReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (ext == "vtp")
  {
    auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else
  {
    std::fprintf(stderr, "error: '%s': unsupported file type '.%s' (use .obj, .ply or .vtp)\n", path.c_str(),
      ext.c_str());
    return nullptr;
  }
  reader->Update();
  vtkPolyData* out = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!out || out->GetNumberOfPoints() == 0)
  {
    std::fprintf(stderr, "error: '%s' holds no points (unreadable or empty)\n", path.c_str());
    return nullptr;
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(out->GetPoints());
  cloud->GetPointData()->ShallowCopy(out->GetPointData());
  return cloud;
}

/// A progress line: redrawn in place on a terminal, one line per quarter in a log.
void showProgress(vtkObject*, unsigned long, void* clientData, void* callData)
{
  static int lastStep = -1;
  static const void* lastStage = nullptr;
  const double f = *static_cast<double*>(callData);
  if (clientData != lastStage)
  {
    lastStage = clientData;
    lastStep = -1;
  }
  const bool tty = isatty(fileno(stderr)) != 0;
  const int step = static_cast<int>(f * (tty ? 100 : 4));
  if (step == lastStep)
  {
    return;
  }
  lastStep = step;
  std::fprintf(stderr, tty ? "\r  %-26s %3.0f%%" : "  %-26s %3.0f%%\n", static_cast<const char*>(clientData),
    100.0 * f);
  if (tty && f >= 1.0)
  {
    std::fprintf(stderr, "\n");
  }
}

template <typename Filter>
double runStage(Filter* f, const char* label)
{
  vtkNew<vtkCallbackCommand> progress;
  progress->SetCallback(showProgress);
  progress->SetClientData(const_cast<char*>(label));
  f->AddObserver(vtkCommand::ProgressEvent, progress);
  const auto t0 = std::chrono::steady_clock::now();
  f->Update();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

} // namespace

int main(int argc, char* argv[])
{
  const std::string input = argc > 1 ? argv[1] : GLS_DEFAULT_INPUT;
  const std::string output = argc > 2 ? argv[2] : "gls-result.vtp";
  auto cloud = readCloud(input);
  if (!cloud)
  {
    return 1;
  }
  std::printf("input: %s, %lld points\n", input.c_str(), static_cast<long long>(cloud->GetNumberOfPoints()));

  vtkNew<vtkGLSNormalEstimation> normals;
  normals->SetInputData(cloud);
  const bool hasNormals = cloud->GetPointData()->GetNormals() != nullptr;
  double seconds = 0.0;
  vtkAlgorithm* last = normals;
  if (!hasNormals)
  {
    seconds += runStage(normals.Get(), "normals");
  }
  vtkNew<vtkGLSScaleSpace> scaleSpace;
  if (hasNormals)
  {
    scaleSpace->SetInputData(cloud);
  }
  else
  {
    scaleSpace->SetInputConnection(last->GetOutputPort());
  }
  seconds += runStage(scaleSpace.Get(), "scale space (20 scales)");
  vtkNew<vtkGLSGeometricVariation> variation;
  variation->SetInputConnection(scaleSpace->GetOutputPort());
  seconds += runStage(variation.Get(), "geometric variation");
  vtkNew<vtkGLSContinuousFeatures> features;
  features->SetInputConnection(variation->GetOutputPort());
  seconds += runStage(features.Get(), "continuous features");
  if (features->GetOutput()->GetPointData()->GetArray("GLSFeature") == nullptr)
  {
    std::fprintf(stderr, "error: the pipeline failed (see the messages above)\n");
    return 1;
  }

  vtkDataArray* f = features->GetOutput()->GetPointData()->GetArray("GLSFeature");
  double range[2];
  f->GetRange(range);
  std::printf("pipeline time: %.3f s; feature range [%.3f, %.3f]\n", seconds, range[0], range[1]);

  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetFileName(output.c_str());
  writer->SetInputConnection(features->GetOutputPort());
  // Inline binary: ParaView 5.11's reader fails on some appended files whose header holds many component names.
  writer->SetDataModeToBinary();
  writer->SetCompressorTypeToZLib();
  writer->SetHeaderTypeToUInt64();
  if (writer->Write() != 1)
  {
    std::fprintf(stderr, "error: cannot write '%s'\n", output.c_str());
    return 1;
  }
  std::printf("wrote %s\n", output.c_str());
  return 0;
}
