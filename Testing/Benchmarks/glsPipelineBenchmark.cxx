// Full GLS pipeline benchmark on the bundled bunny sampled by area (normals interpolated from the mesh), with the
// straightforward per-scale evaluation (one neighbour query and one fit per scale) measured in the same run.
//
//   glsPipelineBenchmark [--points N (173000)] [--scales S (20)] [--threads T (0 = all)] [--skip-per-scale]
//                        [--backend cpu|cuda|auto (cpu)] [--repeat R (1)]
//
// --backend cuda runs the fused one-pass measurement on the GPU (R runs, ms per run reported).
//
// Scales: S quadratic scales from 0.8% to 8% of the bounding-box diagonal. Prints wall time per stage, points x
// scales per second, CPU utilisation ((user + sys) / wall) and peak memory, and the ratio per-scale / one-pass for
// the scale-space + nu + feature computation (both fused, same sink), checking that both give the same features.
#include "MeshSampler.h"

#include "vtkGLSContinuousFeatures.h"
#include "vtkGLSGeometricVariation.h"
#include "vtkGLSNormalEstimation.h"
#include "vtkGLSScaleSpace.h"

#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include "gls/Backend.h"
#include "gls/ScaleAnalysis.h"
#include "gls/VariationSink.h"
#include "gls/ScaleSampling.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace
{

struct Clock
{
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  double cpu = cpuSeconds();
  static double cpuSeconds()
  {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
  }
  double seconds() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - this->wall).count();
  }
  double utilisation() const { return (cpuSeconds() - this->cpu) / std::max(this->seconds(), 1e-9); }
};

double peakMemoryMiB()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

void report(const char* stage, const Clock& c, double pointScales)
{
  const double s = c.seconds();
  std::printf("%-40s %9.3f s  %8.2f Mpoint-scales/s  CPU %4.0f%%\n", stage, s, pointScales / s / 1e6,
    100.0 * c.utilisation());
}

} // namespace

int main(int argc, char* argv[])
{
  long long count = 173000;
  int S = 20, threads = 0;
  bool perScale = true;
  int repeat = 1;
  gls::Backend backend = gls::Backend::CPU;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--points") && i + 1 < argc)
    {
      count = std::atoll(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--scales") && i + 1 < argc)
    {
      S = std::atoi(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc)
    {
      threads = std::atoi(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc)
    {
      repeat = std::max(1, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--backend") && i + 1 < argc)
    {
      const std::string b = argv[++i];
      backend = b == "cuda" ? gls::Backend::CUDA : b == "auto" ? gls::Backend::Auto : gls::Backend::CPU;
    }
    else if (!std::strcmp(argv[i], "--skip-per-scale"))
    {
      perScale = false;
    }
    else
    {
      std::fprintf(stderr, "usage: %s [--points N] [--scales S] [--threads T] [--skip-per-scale] "
                           "[--backend cpu|cuda|auto] [--repeat R]\n", argv[0]);
      return 2;
    }
  }

  auto cloud = sampleMeshSurface(GLS_BENCHMARK_MODEL, count, 1);
  if (!cloud)
  {
    std::fprintf(stderr, "error: cannot read %s\n", GLS_BENCHMARK_MODEL);
    return 1;
  }
  const double n = static_cast<double>(count);
  std::printf("bunny sampled to %lld points, %d quadratic scales 0.8%%-8%% of the diagonal, %d threads\n", count, S,
    gls::resolveThreadCount(threads));

  // The full pipeline, as a user runs it: normals from the points alone, then the stored scale space.
  vtkNew<vtkPolyData> points;
  points->SetPoints(cloud->GetPoints());
  Clock total;
  Clock c;
  vtkNew<vtkGLSNormalEstimation> normals;
  normals->SetInputData(points);
  normals->SetNumberOfThreads(threads);
  normals->Update();
  report("normals (k = 16, MST orientation)", c, n);
  c = Clock();
  vtkNew<vtkGLSScaleSpace> scaleSpace;
  scaleSpace->SetInputConnection(normals->GetOutputPort());
  scaleSpace->SetNumberOfScales(S);
  scaleSpace->SetNumberOfThreads(threads);
  scaleSpace->Update();
  report("scale space (all arrays stored)", c, n * S);
  c = Clock();
  vtkNew<vtkGLSGeometricVariation> variation;
  variation->SetInputConnection(scaleSpace->GetOutputPort());
  variation->SetNumberOfThreads(threads);
  variation->Update();
  report("geometric variation (from stored)", c, n * S);
  c = Clock();
  vtkNew<vtkGLSContinuousFeatures> features;
  features->SetInputConnection(variation->GetOutputPort());
  features->Update();
  report("continuous features (from stored nu)", c, n * S);
  report("FULL PIPELINE normals+scales+nu+features", total, n * S);
  std::printf("peak memory so far: %.0f MiB\n", peakMemoryMiB());

  // One-pass versus per-scale, same points, mesh normals, same fused feature sink.
  std::vector<double> xyz(3 * count), nrm(3 * count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    cloud->GetPoint(i, &xyz[3 * i]);
    cloud->GetPointData()->GetNormals()->GetTuple(i, &nrm[3 * i]);
  }
  double b[6];
  cloud->GetBounds(b);
  const double diag = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
    (b[5] - b[4]) * (b[5] - b[4]));
  gls::ScaleSpaceSettings settings;
  settings.scales = gls::sampleScales(0.008 * diag, 0.08 * diag, S, gls::ScaleSampling::Quadratic);
  settings.parallel.threads = threads;
  settings.backend = backend;
  gls::ScaleSpaceEngine engine(xyz.data(), nrm.data(), static_cast<std::size_t>(count), settings);
  const int T = gls::resolveThreadCount(threads);
  std::vector<double> fOnePass(count), fPerScale(count);
  const gls::VariationReductionSink::Reducer feature = [&settings](const double* nu) {
    return gls::continuousFeature(
      nu, settings.scales.data(), static_cast<int>(settings.scales.size()), 0.1, gls::FeatureMeasure::Scale);
  };
  gls::VariationReductionSink a(settings.scales, T, {}, feature, fOnePass.data());
  gls::RunReport used;
  double onePass = 0.0;
  for (int r = 0; r < repeat; ++r)
  {
    c = Clock();
    engine.run(a, nullptr, nullptr, &used);
    onePass = c.seconds();
    report(used.used == gls::Backend::CUDA ? "one-pass scales+nu+features (fused, CUDA)"
                                           : "one-pass scales+nu+features (fused, CPU)",
      c, n * S);
  }
  std::printf("one-pass on %s: %.1f ms per run%s%s\n", gls::backendName(used.used), 1e3 * onePass,
    used.fallbackReason.empty() ? "" : "; CUDA fell back: ", used.fallbackReason.c_str());
  if (perScale)
  {
    gls::ScaleSpaceSettings reference = settings; // the same grid, the per-scale evaluator, on the CPU
    reference.method = gls::EvaluationMethod::PerScale;
    reference.backend = gls::Backend::CPU;
    const gls::ScaleSpaceEngine referenceEngine(xyz.data(), nrm.data(), static_cast<std::size_t>(count), reference);
    c = Clock();
    gls::VariationReductionSink p(settings.scales, T, {}, feature, fPerScale.data());
    referenceEngine.run(p);
    const double slow = c.seconds();
    report("per-scale scales+nu+features (fused)", c, n * S);
    double worst = 0.0;
    for (long long i = 0; i < count; ++i)
    {
      if (std::isnan(fOnePass[i]) != std::isnan(fPerScale[i]))
      {
        worst = INFINITY;
      }
      else if (!std::isnan(fOnePass[i]))
      {
        worst = std::max(worst, std::abs(fOnePass[i] - fPerScale[i]));
      }
    }
    std::printf("per-scale / one-pass time ratio: %.1fx; max |feature difference|: %.2e\n", slow / onePass, worst);
  }
  std::printf("peak memory: %.0f MiB\n", peakMemoryMiB());
  return 0;
}
