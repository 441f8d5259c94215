// Real scan sizes: the multi-resolution evaluation against the exact one pass (docs/performance.md, "Large scans").
//
//   glsLargeScanBenchmark [--case L1|L2|L3|normals|directions|accuracy|all (all)] [--models bunny,rocker-arm]
//                         [--threads T (2)] [--points N (L1: 10000000; L2 and accuracy: 1000000)]
//                         [--sizes a,b,... (L3)] [--accuracies e1,e2,... (0.1,0.2,0.3)]
//                         [--subset M (accuracy: every point)] [--distances k1,k2,... (linearized: 10,0; accuracy: 10)]
//                         [--rounds R (2)]
//
// Every cloud is a bundled mesh sampled by area to N points, normals interpolated from the mesh; 20 quadratic
// scales 0.8% to 8% of the diagonal; the fused continuous features (nu on the fly, O(N) memory).
//   L1: N = 10M, Evaluation Auto: wall time and peak memory of the features filter (each run in its own process,
//       so the peak is its own; it includes the sampled cloud). Target: under 60 s and 4 GiB.
//   L2: N = 1M, Exact and Auto in the same process: the speed-up (target: at least 10).
//   L3: Auto at 0.3M, 1M, 3M, 10M points (and Exact at 0.3M; L2 has it at 1M): time per point.
//   normals: N = 10M, the points alone through GLS Normal Estimation with its defaults (orientation included): wall
//       time and peak memory (its own process; the peak includes the sampled cloud), and the share of the estimated
//       normals within 5 degrees of the mesh's interpolated normals and pointing their way. Target: L1's budget.
//   accuracy: N = 1M, the core engine exact and at each accuracy, every point and scale compared (p99 and max):
//       |f - f_exact| (sigma of the exact run), |t kappa - t kappa_exact|, |tau - tau_exact| / t, the angle between
//       eta and eta_exact (degrees), |phi - phi_exact|, |nu - nu_exact| / (nu_exact + median nu_exact), and the
//       share of points whose first pertinent scale moves by more than one scale step; PASS/FAIL against the
//       targets at the default accuracy (and linearizedDistance). With --subset M, every (N / M)-th point only (both
//       runs), so that 10M points can be compared: the exact pass costs O(N) per point. With --distances, each
//       accuracy at each linearizedDistance K (the far cells' effect on the errors).
//   directions: N = 10M, Evaluation Auto, float32 outputs as the main job asks, each run in its own process: the
//       fused features with their scale summary, the same with DirectionSummary (the steadiest principal directions
//       from the same fit: the main job's default pass) and GLS Principal Directions alone: wall time, peak memory
//       and the ratio of the first two (the principal curvatures' cost at scale; no target: reported).
//   linearized (not in all): N = 10M, the core engine alone at the default accuracy with each linearizedDistance K
//       (0: no linearized far cells), alternately for R rounds in one process: build and run times side by side.
#include "CommaList.h"
#include "MeshSampler.h"

#include "vtkGLSContinuousFeatures.h"
#include "vtkGLSNormalEstimation.h"
#include "vtkGLSPrincipalDirections.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkSmartPointer.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include "gls/Descriptors.h"
#include "gls/Evaluation.h"
#include "gls/MultiresolutionReferenceWalk.h"
#include "gls/ScaleAnalysis.h"
#include "gls/ScaleSampling.h"
#include "gls/ScaleSpaceEngine.h"
#include "gls/VariationSink.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace
{

constexpr int kScales = 20;

double now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double peakMemoryMiB()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

std::string modelPath(const std::string& model)
{
  return std::string(GLS_BENCHMARK_DATA_DIR) + "/" + (model == "bunny" ? "stanford-bunny" : model) + ".obj";
}

/// Runs f in a child process (its peak memory is its own) and waits; false if the child failed.
bool inChild(const std::function<int()>& f)
{
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid == 0)
  {
    const int rc = f();
    std::fflush(stdout);
    _exit(rc);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

/// The features filter on `cloud` with `evaluation`; prints and returns the wall time, or -1 on failure.
double runFeatures(vtkPolyData* cloud, int evaluation, int threads, double accuracy, std::vector<double>* f = nullptr,
  std::string* used = nullptr)
{
  vtkNew<vtkGLSContinuousFeatures> features;
  features->SetInputData(cloud);
  features->SetNumberOfScales(kScales);
  features->SetNumberOfThreads(threads);
  features->SetEvaluation(evaluation);
  features->SetAccuracy(accuracy);
  const double t0 = now();
  features->Update();
  const double wall = now() - t0;
  vtkDataArray* a = features->GetOutput()->GetPointData()->GetArray("GLSFeature");
  if (!a)
  {
    std::printf("error: the features filter failed\n");
    return -1.0;
  }
  if (f)
  {
    f->resize(static_cast<std::size_t>(a->GetNumberOfTuples()));
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      (*f)[static_cast<std::size_t>(i)] = a->GetComponent(i, 0);
    }
  }
  if (used)
  {
    *used = features->GetLastEvaluationUsed();
  }
  return wall;
}

int caseL1(const std::vector<std::string>& models, long long n, int threads, double accuracy)
{
  std::printf("\n== L1: %lld points, Evaluation Auto, fused features, %d threads (target: < 60 s, < 4 GiB)\n", n,
    threads);
  std::printf("%-12s %10s %12s %12s %s\n", "model", "wall s", "peak MiB", "evaluation", "verdict");
  for (const std::string& model : models)
  {
    inChild([&] {
      auto cloud = sampleMeshSurface(modelPath(model), n, 1);
      if (!cloud)
      {
        return 1;
      }
      std::string used;
      const double wall = runFeatures(cloud, 0, threads, accuracy, nullptr, &used);
      const double peak = peakMemoryMiB();
      std::printf("%-12s %10.1f %12.0f %12s %s\n", model.c_str(), wall, peak, used.c_str(),
        wall >= 0.0 && wall < 60.0 && peak < 4096.0 ? "PASS" : "FAIL");
      return wall >= 0.0 ? 0 : 1;
    });
  }
  return 0;
}

int caseDirections(const std::vector<std::string>& models, long long n, int threads, double accuracy)
{
  std::printf("\n== directions: %lld points, Evaluation Auto, %d threads, each run in its own process: the fused "
              "features with their summary (the main job's pass with --no-directions), the same with "
              "DirectionSummary (its default pass), and GLS Principal Directions alone\n", n, threads);
  std::printf("%-12s %12s %10s %12s %10s %8s %12s %10s\n", "model", "features s", "peak MiB", "+directions",
    "peak MiB", "ratio", "alone s", "peak MiB");
  for (const std::string& model : models)
  {
    double wall[3] = { -1.0, -1.0, -1.0 }, peak[3] = { 0.0, 0.0, 0.0 };
    for (int pass = 0; pass < 3; ++pass)
    {
      // The child reports through a pipe: its time and peak.
      int channel[2];
      if (pipe(channel) != 0)
      {
        return 1;
      }
      inChild([&] {
        close(channel[0]);
        auto cloud = sampleMeshSurface(modelPath(model), n, 1);
        if (!cloud)
        {
          return 1;
        }
        vtkSmartPointer<vtkGLSScaleFilterBase> filter;
        if (pass < 2)
        {
          vtkNew<vtkGLSContinuousFeatures> features;
          features->ScaleSummaryOn();
          features->SetDirectionSummary(pass == 1);
          features->SetOutputPrecision(vtkAlgorithm::SINGLE_PRECISION);
          filter = features;
        }
        else
        {
          vtkNew<vtkGLSPrincipalDirections> directions;
          directions->SetOutputPrecision(vtkAlgorithm::SINGLE_PRECISION);
          filter = directions;
        }
        filter->SetInputData(cloud);
        filter->SetNumberOfScales(kScales);
        filter->SetNumberOfThreads(threads);
        filter->SetAccuracy(accuracy);
        const double t0 = now();
        filter->Update();
        const bool done =
          vtkPolyData::SafeDownCast(filter->GetOutputDataObject(0))->GetPointData()->GetArray("GLSRidgeValley");
        double measured[2] = { done || pass == 0 ? now() - t0 : -1.0, peakMemoryMiB() };
        const bool sent = write(channel[1], measured, sizeof measured) == static_cast<ssize_t>(sizeof measured);
        close(channel[1]);
        return sent && measured[0] >= 0.0 ? 0 : 1;
      });
      close(channel[1]);
      double measured[2];
      if (read(channel[0], measured, sizeof measured) == static_cast<ssize_t>(sizeof measured))
      {
        wall[pass] = measured[0];
        peak[pass] = measured[1];
      }
      close(channel[0]);
    }
    std::printf("%-12s %12.1f %10.0f %12.1f %10.0f %7.2fx %12.1f %10.0f\n", model.c_str(), wall[0], peak[0], wall[1],
      peak[1], wall[0] > 0.0 ? wall[1] / wall[0] : std::nan(""), wall[2], peak[2]);
  }
  return 0;
}

int caseNormals(const std::vector<std::string>& models, long long n, int threads)
{
  std::printf("\n== normals: %lld points, GLS Normal Estimation with its defaults, %d threads (target: < 60 s, "
              "< 4 GiB)\n",
    n, threads);
  std::printf("%-12s %10s %12s %14s %14s %10s %s\n", "model", "wall s", "peak MiB", "within 5 deg", "wrong way",
    "NaN", "verdict");
  for (const std::string& model : models)
  {
    inChild([&] {
      auto sampled = sampleMeshSurface(modelPath(model), n, 1);
      if (!sampled)
      {
        return 1;
      }
      vtkNew<vtkPolyData> points;
      points->SetPoints(sampled->GetPoints());
      vtkNew<vtkGLSNormalEstimation> normals;
      normals->SetInputData(points);
      normals->SetNumberOfThreads(threads);
      const double t0 = now();
      normals->Update();
      const double wall = now() - t0;
      const double peak = peakMemoryMiB();
      vtkDataArray* estimated = normals->GetOutput()->GetPointData()->GetNormals();
      vtkDataArray* truth = sampled->GetPointData()->GetNormals();
      if (!estimated || !truth)
      {
        std::printf("error: no normals\n");
        return 1;
      }
      long long within = 0, wrong = 0, undefined = 0;
      const double cos5 = std::cos(5.0 * 3.14159265358979323846 / 180.0);
      for (vtkIdType i = 0; i < estimated->GetNumberOfTuples(); ++i)
      {
        double e[3], t[3];
        estimated->GetTuple(i, e);
        truth->GetTuple(i, t);
        const double c = e[0] * t[0] + e[1] * t[1] + e[2] * t[2];
        const double lengths =
          std::sqrt((e[0] * e[0] + e[1] * e[1] + e[2] * e[2]) * (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]));
        if (!std::isfinite(c) || !(lengths > 0.0))
        {
          ++undefined;
          continue;
        }
        within += std::abs(c) >= cos5 * lengths ? 1 : 0;
        wrong += c < 0.0 ? 1 : 0;
      }
      const double N = static_cast<double>(estimated->GetNumberOfTuples());
      std::printf("%-12s %10.1f %12.0f %13.2f%% %13.2f%% %9.3f%% %s\n", model.c_str(), wall, peak,
        100.0 * within / N, 100.0 * wrong / N, 100.0 * undefined / N,
        wall < 60.0 && peak < 4096.0 ? "PASS" : "FAIL");
      return 0;
    });
  }
  return 0;
}

int caseL2(const std::vector<std::string>& models, long long n, int threads, double accuracy)
{
  std::printf("\n== L2: %lld points, Exact and Auto in one run, fused features, %d threads (target: >= 10x)\n", n,
    threads);
  std::printf("%-12s %10s %10s %10s %12s %12s %s\n", "model", "exact s", "auto s", "speed-up", "f p99 diff",
    "f max diff", "verdict");
  for (const std::string& model : models)
  {
    inChild([&] {
      auto cloud = sampleMeshSurface(modelPath(model), n, 1);
      std::vector<double> fe, fa;
      std::string used;
      const double exact = runFeatures(cloud, 1, threads, accuracy, &fe);
      const double fast = runFeatures(cloud, 0, threads, accuracy, &fa, &used);
      std::vector<double> d;
      for (std::size_t i = 0; i < fe.size(); ++i)
      {
        if (std::isfinite(fe[i]) && std::isfinite(fa[i]))
        {
          d.push_back(std::abs(fe[i] - fa[i]));
        }
      }
      std::sort(d.begin(), d.end());
      const double p99 = d.empty() ? NAN : d[d.size() * 99 / 100], worst = d.empty() ? NAN : d.back();
      std::printf("%-12s %10.1f %10.1f %9.1fx %12.4f %12.4f %s (%s)\n", model.c_str(), exact, fast, exact / fast,
        p99, worst, exact / fast >= 10.0 ? "PASS" : "FAIL", used.c_str());
      return 0;
    });
  }
  return 0;
}

int caseL3(const std::vector<std::string>& models, const std::vector<long long>& sizes, int threads,
  double accuracy)
{
  std::printf("\n== L3: cost against N at the same relative scales, fused features, %d threads\n", threads);
  std::printf("%-12s %12s %12s %14s %12s %14s\n", "model", "points", "auto s", "auto us/point", "exact s",
    "exact us/point");
  for (const std::string& model : models)
  {
    for (long long n : sizes)
    {
      inChild([&] {
        auto cloud = sampleMeshSurface(modelPath(model), n, 1);
        const double fast = runFeatures(cloud, 0, threads, accuracy);
        const double exact = n <= 300000 ? runFeatures(cloud, 1, threads, accuracy) : NAN;
        std::printf("%-12s %12lld %12.1f %14.2f %12.1f %14.2f\n", model.c_str(), n, fast, 1e6 * fast / n, exact,
          1e6 * exact / n);
        return 0;
      });
    }
  }
  return 0;
}

/// What the accuracy comparison keeps of the exact run, per point and scale.
struct ExactRow
{
  float tauOverT, tKappa, phi, eta[3];
  double nu;
};

/// Percentiles from a log-spaced histogram (1e-16 to 1e4, 100 bins per decade), per thread then merged.
struct Histogram
{
  static constexpr int kBins = 2000;
  std::vector<double> count = std::vector<double>(kBins + 1, 0.0);
  double worst = 0.0;
  void add(double v)
  {
    if (!(v >= 0.0))
    {
      return;
    }
    worst = std::max(worst, v);
    const int b = v <= 1e-16 ? 0 : std::min(kBins, static_cast<int>(100.0 * (std::log10(v) + 16.0)) + 1);
    count[static_cast<std::size_t>(b)] += 1.0;
  }
  void merge(const Histogram& h)
  {
    for (int b = 0; b <= kBins; ++b)
    {
      count[static_cast<std::size_t>(b)] += h.count[static_cast<std::size_t>(b)];
    }
    worst = std::max(worst, h.worst);
  }
  double quantile(double q) const
  {
    double total = 0.0;
    for (double c : count)
    {
      total += c;
    }
    double seen = 0.0;
    for (int b = 0; b <= kBins; ++b)
    {
      seen += count[static_cast<std::size_t>(b)];
      if (seen >= q * total)
      {
        return b == 0 ? 1e-16 : std::pow(10.0, b / 100.0 - 16.0); // the bin's upper edge
      }
    }
    return worst;
  }
};

enum Metric
{
  F,
  KAPPA,
  TAU,
  ETA,
  PHI,
  NU,
  METRICS
};

int firstPertinent(const double* nu, const std::vector<double>& scales)
{
  double found[kScales];
  const int m = gls::pertinentScales(nu, scales.data(), static_cast<int>(scales.size()), kScales, found);
  if (m == 0)
  {
    return -1;
  }
  return static_cast<int>(std::lower_bound(scales.begin(), scales.end(), found[0]) - scales.begin());
}

/// The points compared: every point (ids empty), or every (N / M)-th point; slot(id) is a point's row.
struct Compared
{
  std::vector<std::uint64_t> ids;
  std::vector<std::uint32_t> slots; ///< per point id, its row (with ids)

  Compared(std::size_t n, std::size_t subset)
  {
    if (subset == 0 || subset >= n)
    {
      return;
    }
    slots.assign(n, 0);
    const std::size_t stride = n / subset;
    for (std::size_t m = 0; m < subset; ++m)
    {
      ids.push_back(m * stride);
      slots[m * stride] = static_cast<std::uint32_t>(m);
    }
  }
  std::size_t count(std::size_t n) const { return ids.empty() ? n : ids.size(); }
  std::size_t slot(std::uint64_t id) const { return ids.empty() ? static_cast<std::size_t>(id) : slots[id]; }
  const std::vector<std::uint64_t>* subset() const { return ids.empty() ? nullptr : &ids; }
};

class ExactSink : public gls::ScaleSampleSink
{
public:
  ExactSink(const std::vector<double>& scales, const Compared& compared, std::size_t n)
    : Scales(scales)
    , Points(compared)
    , Rows(compared.count(n) * scales.size())
    , Neighbors(compared.count(n))
  {
  }
  void consume(std::uint64_t id, const gls::ScaleSample* s, int) override
  {
    const std::size_t slot = this->Points.slot(id);
    for (std::size_t k = 0; k < this->Scales.size(); ++k)
    {
      const double t = this->Scales[k];
      ExactRow& r = this->Rows[slot * this->Scales.size() + k];
      r = { static_cast<float>(s[k].tau / t), static_cast<float>(s[k].kappa * t), static_cast<float>(s[k].phi),
        { static_cast<float>(s[k].eta.x), static_cast<float>(s[k].eta.y), static_cast<float>(s[k].eta.z) },
        gls::geometricVariation(s[k], t, gls::VariationWeights{}) };
    }
    this->Neighbors[slot] = s[this->Scales.size() - 1].neighbors;
  }
  const std::vector<double>& Scales;
  const Compared& Points;
  std::vector<ExactRow> Rows;     ///< per compared point (slot) and scale
  std::vector<double> Neighbors; ///< in the largest ball, per compared point
};

class CompareSink : public gls::ScaleSampleSink
{
public:
  CompareSink(const std::vector<double>& scales, const Compared& compared, const std::vector<ExactRow>& exact,
    const std::vector<double>& f, const std::vector<int>& first, double sigma, double medianNu, int threads)
    : Scales(scales)
    , Points(compared)
    , Exact(exact)
    , ExactF(f)
    , ExactFirst(first)
    , Sigma(sigma)
    , MedianNu(medianNu)
    , H(static_cast<std::size_t>(threads), std::vector<Histogram>(METRICS))
    , Moved(static_cast<std::size_t>(threads), 0.0)
    , Nu(static_cast<std::size_t>(threads), std::vector<double>(scales.size()))
  {
  }
  void consume(std::uint64_t id, const gls::ScaleSample* s, int thread) override
  {
    std::vector<Histogram>& h = this->H[static_cast<std::size_t>(thread)];
    std::vector<double>& nu = this->Nu[static_cast<std::size_t>(thread)];
    const std::size_t S = this->Scales.size();
    const std::size_t slot = this->Points.slot(id);
    for (std::size_t k = 0; k < S; ++k)
    {
      const double t = this->Scales[k];
      const ExactRow& e = this->Exact[slot * S + k];
      nu[k] = gls::geometricVariation(s[k], t, gls::VariationWeights{});
      if (!s[k].valid || !std::isfinite(e.tKappa))
      {
        continue;
      }
      h[KAPPA].add(std::abs(s[k].kappa * t - e.tKappa));
      h[TAU].add(std::abs(s[k].tau / t - e.tauOverT));
      const double c = s[k].eta.x * e.eta[0] + s[k].eta.y * e.eta[1] + s[k].eta.z * e.eta[2];
      h[ETA].add(std::acos(std::max(-1.0, std::min(1.0, c))) * 180.0 / M_PI);
      h[PHI].add(std::abs(s[k].phi - e.phi));
      h[NU].add(std::abs(nu[k] - e.nu) / (e.nu + this->MedianNu));
    }
    const double f = gls::continuousFeature(nu.data(), this->Scales.data(), static_cast<int>(S), this->Sigma,
      gls::FeatureMeasure::Scale);
    if (std::isfinite(f) && std::isfinite(this->ExactF[slot]))
    {
      h[F].add(std::abs(f - this->ExactF[slot]));
    }
    const int first = firstPertinent(nu.data(), this->Scales);
    const int e = this->ExactFirst[slot];
    if ((first < 0) != (e < 0) || std::abs(first - e) > 1)
    {
      this->Moved[static_cast<std::size_t>(thread)] += 1.0;
    }
  }
  const std::vector<double>& Scales;
  const Compared& Points;
  const std::vector<ExactRow>& Exact;
  const std::vector<double>& ExactF;
  const std::vector<int>& ExactFirst;
  double Sigma, MedianNu;
  std::vector<std::vector<Histogram>> H;
  std::vector<double> Moved;
  std::vector<std::vector<double>> Nu;
};

/// The model sampled to n points as the core engine reads them (xyz, nrm), and the benchmark's settings for it.
gls::ScaleSpaceSettings coreSettings(
  const std::string& model, long long n, int threads, std::vector<double>& xyz, std::vector<double>& nrm)
{
  auto cloud = sampleMeshSurface(modelPath(model), n, 1);
  xyz.resize(3 * static_cast<std::size_t>(n));
  nrm.resize(3 * static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    cloud->GetPoint(i, &xyz[3 * static_cast<std::size_t>(i)]);
    cloud->GetPointData()->GetNormals()->GetTuple(i, &nrm[3 * static_cast<std::size_t>(i)]);
  }
  double b[6];
  cloud->GetBounds(b);
  const double diag =
    std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
  gls::ScaleSpaceSettings settings;
  settings.scales = gls::sampleScales(0.008 * diag, 0.08 * diag, kScales, gls::ScaleSampling::Quadratic);
  settings.parallel.threads = threads;
  return settings;
}

/// The core engine alone (no filter), Evaluation Multiresolution at the default accuracy, fused features, with each
/// linearizedDistance in turn, `rounds` times alternately: the far cells' effect side by side in one process.
int caseLinearized(const std::vector<std::string>& models, long long n, int threads, const std::vector<double>& distances,
  int rounds)
{
  std::printf("\n== Linearized far cells side by side: the core engine, %lld points, fused features, %d threads\n", n,
    threads);
  std::printf("%-12s %6s %8s %10s %10s %10s\n", "model", "round", "K", "build s", "run s", "us/point");
  for (const std::string& model : models)
  {
    std::vector<double> xyz, nrm;
    gls::ScaleSpaceSettings settings = coreSettings(model, n, threads, xyz, nrm);
    settings.evaluation = gls::Evaluation::Multiresolution;
    const std::size_t N = static_cast<std::size_t>(n);
    std::vector<double> f(N);
    for (int round = 1; round <= rounds; ++round)
    {
      for (double k : distances)
      {
        settings.multiresolution.linearizedDistance = k;
        const double t0 = now();
        gls::ScaleSpaceEngine engine(xyz.data(), nrm.data(), N, settings);
        const double built = now();
        const std::vector<double>& scales = engine.scales();
        gls::VariationReductionSink sink(scales, gls::resolveThreadCount(threads), {},
          [&scales](const double* nu) {
            return gls::continuousFeature(nu, scales.data(), kScales, 0.1, gls::FeatureMeasure::Scale);
          },
          f.data());
        engine.run(sink);
        const double done = now();
        std::printf("%-12s %6d %8g %10.1f %10.1f %10.2f\n", model.c_str(), round, k, built - t0, done - built,
          1e6 * (done - built) / static_cast<double>(n));
        std::fflush(stdout);
      }
    }
  }
  return 0;
}

int caseAccuracy(const std::vector<std::string>& models, long long n, int threads, const std::vector<double>& eps,
  const std::vector<double>& distances, long long subset)
{
  if (subset > 0 && subset < n)
  {
    std::printf("\n== Accuracy against exact: %lld points, every %lld-th point (%lld) and every scale, %d threads\n",
      n, n / subset, subset, threads);
  }
  else
  {
    std::printf("\n== Accuracy against exact: %lld points, every point and scale, %d threads\n", n, threads);
  }
  const double targets[METRICS] = { 0.02, 0.01, 0.005, 0.5, 0.01, 0.1 };
  const char* names[METRICS] = { "f", "t kappa", "tau/t", "eta deg", "phi", "nu rel" };
  bool allPass = true;
  for (const std::string& model : models)
  {
    std::vector<double> xyz, nrm;
    gls::ScaleSpaceSettings settings = coreSettings(model, n, threads, xyz, nrm);
    const int T = gls::resolveThreadCount(threads);
    const std::size_t total = static_cast<std::size_t>(n);
    const Compared compared(total, static_cast<std::size_t>(subset > 0 ? subset : 0));
    const std::size_t N = compared.count(total); // the points compared
    const std::vector<double>& scales = settings.scales;
    double t0 = now();
    ExactSink exact(scales, compared, total);
    {
      gls::ScaleSpaceEngine engine(xyz.data(), nrm.data(), total, settings);
      engine.run(exact, compared.subset());
    }
    double largestBall = 0.0;
    for (std::size_t i = 0; i < N; ++i)
    {
      largestBall += exact.Neighbors[i];
    }
    largestBall /= static_cast<double>(N);
    const double exactTime = now() - t0;
    // The exact run's sigma (median f 0.28, as the filters' default) and its features and first pertinent scales.
    std::vector<double> nu(N * kScales);
    for (std::size_t i = 0; i < N * kScales; ++i)
    {
      nu[i] = exact.Rows[i].nu;
    }
    const double sigma =
      gls::sigmaForMedianFeature(nu, N, scales.data(), kScales, gls::FeatureMeasure::Scale, 0.28);
    std::vector<double> f(N);
    std::vector<int> first(N);
    for (std::size_t i = 0; i < N; ++i)
    {
      f[i] = gls::continuousFeature(&nu[i * kScales], scales.data(), kScales, sigma, gls::FeatureMeasure::Scale);
      first[i] = firstPertinent(&nu[i * kScales], scales);
    }
    std::vector<double> finite;
    for (double v : nu)
    {
      if (std::isfinite(v))
      {
        finite.push_back(v);
      }
    }
    std::nth_element(finite.begin(), finite.begin() + static_cast<long>(finite.size() / 2), finite.end());
    const double medianNu = finite[finite.size() / 2];
    std::vector<double>().swap(finite);
    std::vector<double>().swap(nu);
    std::printf("\n%s: exact %.1f s, %.0f points per largest ball; sigma %.4g, median nu %.4g\n", model.c_str(),
      exactTime, largestBall, sigma, medianNu);
    std::printf("%-6s %5s %8s %8s %9s", "eps", "K", "time s", "speed-up", "samples");
    for (int m = 0; m < METRICS; ++m)
    {
      std::printf(" %10s p99 %9s", names[m], "max");
    }
    std::printf(" %9s\n", "moved");
    for (std::size_t run = 0; run < eps.size() * distances.size(); ++run)
    {
      const double e = eps[run / distances.size()], k = distances[run % distances.size()];
      gls::ScaleSpaceSettings ms = settings;
      ms.evaluation = gls::Evaluation::Multiresolution;
      ms.multiresolution.accuracy = e;
      ms.multiresolution.linearizedDistance = k;
      t0 = now();
      CompareSink compare(scales, compared, exact.Rows, f, first, sigma, medianNu, T);
      double samples = 0.0; // per point: cells taken whole plus points read one by one, over 1,000 points
      {
        gls::ScaleSpaceEngine engine(xyz.data(), nrm.data(), total, ms);
        engine.run(compare, compared.subset());
        const gls::MultiresolutionView& v = engine.pyramid().view();
        const std::size_t stride = std::max<std::size_t>(1, total / 1000);
        double visited = 0.0;
        for (std::size_t i = 0; i < total; i += stride, visited += 1.0)
        {
          gls::forEachMultiresolutionSample(
            v, { xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] }, scales.back(), scales.front(),
            [&](std::uint32_t, int, bool) { samples += 1.0; }, [&](std::uint32_t) { samples += 1.0; });
        }
        samples /= visited;
      }
      const double time = now() - t0;
      std::vector<Histogram> h(METRICS);
      double moved = 0.0;
      for (int t = 0; t < T; ++t)
      {
        for (int m = 0; m < METRICS; ++m)
        {
          h[static_cast<std::size_t>(m)].merge(compare.H[static_cast<std::size_t>(t)][static_cast<std::size_t>(m)]);
        }
        moved += compare.Moved[static_cast<std::size_t>(t)];
      }
      const bool isDefault = std::abs(e - gls::kDefaultAccuracy) < 1e-12 && k == gls::kLinearizedDistance;
      std::printf("%-6.3g %5g %8.1f %7.1fx %9.0f", e, k, time, exactTime / time, samples);
      for (int m = 0; m < METRICS; ++m)
      {
        const double p99 = h[static_cast<std::size_t>(m)].quantile(0.99);
        const bool pass = p99 <= targets[m];
        allPass = allPass && (!isDefault || pass);
        std::printf(" %10.3g%s %9.3g", p99, isDefault ? (pass ? " ok" : " XX") : "   ",
          h[static_cast<std::size_t>(m)].worst);
      }
      std::printf(" %8.2f%%\n", 100.0 * moved / static_cast<double>(N));
    }
  }
  std::printf("\naccuracy at the default epsilon %.3g (p99 targets f 0.02, t kappa 0.01, tau/t 0.005, eta 0.5 deg, "
              "phi 0.01, nu 0.1; 'ok' = met, 'XX' = missed): %s\n",
    gls::kDefaultAccuracy, allPass ? "PASS" : "FAIL");
  return 0;
}

} // namespace

int main(int argc, char* argv[])
{
  std::string which = "all";
  std::vector<std::string> models = { "bunny", "rocker-arm" };
  int threads = 2;
  long long points = 0;
  std::vector<long long> sizes = { 300000, 1000000, 3000000, 10000000 };
  std::vector<double> eps = { 0.1, 0.2, 0.3 };
  long long subset = 0;
  int rounds = 2;
  std::vector<double> distances = { gls::kLinearizedDistance, 0.0 };
  bool distancesGiven = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    const char* v = i + 1 < argc ? argv[i + 1] : nullptr;
    if (a == "--case" && v)
    {
      which = argv[++i];
    }
    else if (a == "--models" && v)
    {
      models = splitCommaList(argv[++i]);
    }
    else if (a == "--threads" && v)
    {
      threads = std::atoi(argv[++i]);
    }
    else if (a == "--points" && v)
    {
      points = std::atoll(argv[++i]);
    }
    else if (a == "--sizes" && v)
    {
      sizes.clear();
      for (const std::string& s : splitCommaList(argv[++i]))
      {
        sizes.push_back(std::atoll(s.c_str()));
      }
    }
    else if (a == "--subset" && v)
    {
      subset = std::atoll(argv[++i]);
    }
    else if (a == "--rounds" && v)
    {
      rounds = std::atoi(argv[++i]);
    }
    else if (a == "--distances" && v)
    {
      distancesGiven = true;
      distances.clear();
      for (const std::string& s : splitCommaList(argv[++i]))
      {
        distances.push_back(std::atof(s.c_str()));
      }
    }
    else if (a == "--accuracies" && v)
    {
      eps.clear();
      for (const std::string& s : splitCommaList(argv[++i]))
      {
        eps.push_back(std::atof(s.c_str()));
      }
    }
    else
    {
      std::fprintf(stderr,
        "usage: %s [--case L1|L2|L3|normals|directions|accuracy|linearized|all] [--models a,b] [--threads T] "
        "[--points N] [--sizes a,b] [--accuracies e1,e2] [--subset M] [--distances k1,k2] [--rounds R]\n",
        argv[0]);
      return 2;
    }
  }
  const double accuracy = gls::kDefaultAccuracy;
  if (which == "L1" || which == "all")
  {
    caseL1(models, points > 0 ? points : 10000000, threads, accuracy);
  }
  if (which == "L2" || which == "all")
  {
    caseL2(models, points > 0 ? points : 1000000, threads, accuracy);
  }
  if (which == "L3" || which == "all")
  {
    caseL3(models, sizes, threads, accuracy);
  }
  if (which == "normals" || which == "all")
  {
    caseNormals(models, points > 0 ? points : 10000000, threads);
  }
  if (which == "directions" || which == "all")
  {
    caseDirections(models, points > 0 ? points : 10000000, threads, accuracy);
  }
  if (which == "accuracy" || which == "all")
  {
    caseAccuracy(models, points > 0 ? points : 1000000, threads, eps, distancesGiven ? distances :
      std::vector<double>{ gls::kLinearizedDistance }, subset);
  }
  if (which == "linearized")
  {
    caseLinearized(models, points > 0 ? points : 10000000, threads, distances, rounds);
  }
  std::printf("\nlarge-scan benchmark complete\n");
  return 0;
}
