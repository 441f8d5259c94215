// The CUDA backend against the CPU engine, side by side in one process, on a bundled mesh sampled by area (mesh
// normals): the fused continuous features (20 quadratic scales 0.8% to 8% of the box diagonal, nu on the fly), with
// the exact pass and with the multi-resolution one. VTK-free (the core and the test clouds only), so that it builds
// and runs on a GPU machine that has no VTK.
//
//   glsCudaBenchmark [--model NAME.obj (stanford-bunny.obj)] [--points N1,N2,... (1000000)] [--threads T (0 = all)]
//                    [--repeat R (3)] [--exact-up-to N (1000000)] [--accuracy E (the default)]
//
// For each size and each evaluation (Exact only up to --exact-up-to points): the engine's build (grid or pyramid),
// one CPU run, R CUDA runs (the first includes the device's set-up; the best is reported), the GPU/CPU speed-up of
// the best run, and how far the GPU's features are from the CPU's (max |f_gpu - f_cpu|; features in [0, 1]) and
// how many points are NaN on one side only. Without a usable device the CUDA column says why and the run goes on.
#include "CommaList.h"
#include "TestClouds.h"

#include "gls/Backend.h"
#include "gls/ScaleAnalysis.h"
#include "gls/ScaleSampling.h"
#include "gls/ScaleSpaceEngine.h"
#include "gls/VariationSink.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace
{

double secondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// One fused run (scale space, nu and the continuous feature per point); seconds, or a negative value on abort.
double runFeatures(const gls::ScaleSpaceEngine& engine, int threads, std::vector<double>& f, gls::RunReport& report)
{
  const std::vector<double>& scales = engine.scales();
  const gls::VariationReductionSink::Reducer feature = [&scales](const double* nu) {
    return gls::continuousFeature(
      nu, scales.data(), static_cast<int>(scales.size()), 0.1, gls::FeatureMeasure::Scale);
  };
  f.assign(engine.pointCount(), std::numeric_limits<double>::quiet_NaN());
  gls::VariationReductionSink sink(scales, gls::resolveThreadCount(threads), {}, feature, f.data());
  gls::ParallelOptions parallel;
  parallel.threads = threads;
  const auto start = std::chrono::steady_clock::now();
  const bool done = engine.run(sink, nullptr, &parallel, &report);
  return done ? secondsSince(start) : -1.0;
}

} // namespace

int main(int argc, char* argv[])
{
  std::string model = "stanford-bunny.obj";
  std::vector<long long> sizes = { 1000000 };
  int threads = 0, repeat = 3;
  long long exactUpTo = 1000000;
  double accuracy = gls::kDefaultAccuracy;
  for (int i = 1; i < argc; ++i)
  {
    const bool hasValue = i + 1 < argc;
    if (!std::strcmp(argv[i], "--model") && hasValue)
    {
      model = argv[++i];
    }
    else if (!std::strcmp(argv[i], "--points") && hasValue)
    {
      sizes.clear();
      for (const std::string& item : splitCommaList(argv[++i]))
      {
        sizes.push_back(std::atoll(item.c_str()));
      }
    }
    else if (!std::strcmp(argv[i], "--threads") && hasValue)
    {
      threads = std::atoi(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--repeat") && hasValue)
    {
      repeat = std::max(1, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--exact-up-to") && hasValue)
    {
      exactUpTo = std::atoll(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--accuracy") && hasValue)
    {
      accuracy = std::atof(argv[++i]);
    }
    else
    {
      std::fprintf(stderr,
        "usage: %s [--model NAME.obj] [--points N1,N2,...] [--threads T] [--repeat R] [--exact-up-to N] "
        "[--accuracy E]\n",
        argv[0]);
      return 2;
    }
  }
  const gls::CudaAvailability& cuda = gls::cudaAvailability();
  std::printf("CUDA: %s\n", cuda.usable ? cuda.device.c_str() : ("not usable: " + cuda.reason).c_str());
  std::printf("%s, 20 quadratic scales 0.8%%-8%% of the diagonal, fused features, CPU on %d threads, accuracy %g\n",
    model.c_str(), gls::resolveThreadCount(threads), accuracy);
  std::printf("%-10s %-16s %9s %9s %11s %11s %9s %12s %8s\n", "points", "evaluation", "build s", "CPU s",
    "GPU 1st s", "GPU best s", "speed-up", "max |df|", "NaN diff");
  for (long long n : sizes)
  {
    const glstest::Cloud cloud = glstest::sampleObjSurface(glstest::dataFile(model), static_cast<std::size_t>(n), 1);
    if (cloud.size() == 0)
    {
      std::fprintf(stderr, "error: cannot sample %s\n", model.c_str());
      return 1;
    }
    const double diagonal = glstest::boxDiagonal(cloud.points);
    for (gls::Evaluation evaluation : { gls::Evaluation::Exact, gls::Evaluation::Multiresolution })
    {
      if (evaluation == gls::Evaluation::Exact && n > exactUpTo)
      {
        continue;
      }
      gls::ScaleSpaceSettings settings;
      settings.scales = gls::sampleScales(0.008 * diagonal, 0.08 * diagonal, 20, gls::ScaleSampling::Quadratic);
      settings.parallel.threads = threads;
      settings.evaluation = evaluation;
      settings.multiresolution.accuracy = accuracy;
      std::vector<double> fCpu, fGpu;
      gls::RunReport cpuReport, gpuReport;
      double build = 0.0, cpu = 0.0;
      {
        const auto built = std::chrono::steady_clock::now();
        const gls::ScaleSpaceEngine engine(cloud.points.data(), cloud.normals.data(), cloud.size(), settings);
        build = secondsSince(built);
        cpu = runFeatures(engine, threads, fCpu, cpuReport);
      }
      settings.backend = gls::Backend::CUDA; // the same engine, built for the device's evaluator
      const gls::ScaleSpaceEngine device(cloud.points.data(), cloud.normals.data(), cloud.size(), settings);
      double first = 0.0, best = INFINITY;
      for (int r = 0; r < repeat; ++r)
      {
        const double s = runFeatures(device, threads, fGpu, gpuReport);
        first = r == 0 ? s : first;
        best = std::min(best, s);
      }
      double worst = 0.0;
      long long nanDiff = 0;
      for (std::size_t i = 0; i < fCpu.size(); ++i)
      {
        if (std::isnan(fCpu[i]) != std::isnan(fGpu[i]))
        {
          ++nanDiff;
        }
        else if (!std::isnan(fCpu[i]))
        {
          worst = std::max(worst, std::abs(fCpu[i] - fGpu[i]));
        }
      }
      const std::string name = evaluation == gls::Evaluation::Exact ? "exact" : "multiresolution";
      if (gpuReport.used != gls::Backend::CUDA)
      {
        std::printf("%-10lld %-16s %9.2f %9.2f   (GPU run fell back to the CPU: %s)\n", n, name.c_str(), build, cpu,
          gpuReport.fallbackReason.c_str());
        continue;
      }
      std::printf("%-10lld %-16s %9.2f %9.2f %11.3f %11.3f %8.1fx %12.2e %8lld\n", n, name.c_str(), build, cpu, first,
        best, cpu / best, worst, nanDiff);
      std::fflush(stdout);
    }
  }
  std::printf("cuda benchmark complete\n");
  return 0;
}
