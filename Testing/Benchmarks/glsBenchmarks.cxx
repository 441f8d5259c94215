// The performance benchmarks P1-P5 (issue "Performance"), on the bundled bunny sampled by area to 173,000 and
// 1,000,000 points with normals interpolated from the mesh; scales are fractions of the bounding-box diagonal.
//
//   glsBenchmarks --case all|P1|P2|P3|P4|P5|P1-one-pass|C1|C1-multiresolution [--threads T] [--no-peers]
//     [--repeats R]
//
//   P1  scale space + nu, 20 quadratic scales 0.8%-8%, 173k points; against the per-scale evaluation (one ball
//       query and one fit per scale) in the same run, and against a single-thread run (bitwise identical?).
//   P2  as P1 with 1,000 scales (ratio to P1).
//   P3  P1 on 1M points (ratio to P1).
//   P4  normal estimation on 1M points: k = 16 against vtkPCANormalEstimation (SampleSize 16, vtkSMPTools STDThread),
//       same normals up to sign; and a radius giving about 30 neighbours (VTK 9.2's filter has no radius mode).
//       When CMake finds CGAL and TBB, also CGAL's pca_estimate_normals (k = 16, TBB) in the same run.
//   Peers run as processes of their own, when installed (a line says so when not): P1 CloudCompare's -CURV MEAN r
//   at the 20 scales against GLS |kappa|; P4 Open3D's estimate_normals (16 nearest within the ~30-neighbour
//   radius) against GLS k = 16, and CloudCompare's -OCTREE_NORMALS r against GLS over the same radius. Each peer
//   gets GLS's thread count; its compute is timed apart from its start-up and file I/O. --no-peers skips them
//   (CloudCompare's P1 column alone takes minutes).
//   P5  continuous features alone (fused: nothing stored per scale), 1M points, 100 quadratic scales from 0.08% to
//       0.8% of the diagonal: peak memory. Run it in a process of its own (--case P5) so that the peak is its own.
//   P1-one-pass  P1's one-pass row alone (for tuning the kernel).
//   C1  P1's setup with the principal curvatures (ShapeOperatorMoments) against the scale space alone, in the same
//       run, alternating R times (--repeats, 2 by default), exact and multi-resolution: the cost ratios (the targets:
//       at most 1.6x and 1.5x) of the summed CPU times, and of the fastest run of each (on a shared machine, where
//       other load slows some runs, the least disturbed ones). C1-multiresolution: its multi-resolution half.
// Each prints wall time, points x scales per second, neighbour visits per second, CPU utilisation and peak memory.
#include "CloudComparePeer.h"
#include "MeshSampler.h"
#include "Open3DPeer.h"
#include "PeerAgreement.h"
#ifdef GLS_BENCHMARK_WITH_CGAL
#include "CgalNormals.h"
#endif

#include "vtkGLSContinuousFeatures.h"
#include "vtkGLSNormalEstimation.h"

#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPCANormalEstimation.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <Eigen/Eigenvalues>

#include "gls/Descriptors.h"
#include "gls/OnePassKernel.h"
#include "gls/ScaleSampling.h"
#include "gls/ScaleSpaceEngine.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace
{

double cpuSeconds()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double peakMiB()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

struct Timer
{
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  double cpu0 = cpuSeconds();
  double seconds() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - this->start).count();
  }
  double utilisation() const { return (cpuSeconds() - this->cpu0) / std::max(this->seconds(), 1e-9); }
};

struct Cloud
{
  std::vector<double> xyz, normals;
  double diagonal = 0.0;
  std::size_t size() const { return this->xyz.size() / 3; }
};

Cloud bunny(long long count)
{
  auto pd = sampleMeshSurface(GLS_BENCHMARK_MODEL, count, 1);
  Cloud c;
  c.xyz.resize(3 * count);
  c.normals.resize(3 * count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    pd->GetPoint(i, &c.xyz[3 * i]);
    pd->GetPointData()->GetNormals()->GetTuple(i, &c.normals[3 * i]);
  }
  double b[6];
  pd->GetBounds(b);
  c.diagonal = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
  return c;
}

/// Stores nu for every point and scale (the GeometricVariation output), and kappa when asked (for the peers'
/// curvature), and counts the neighbours visited.
class VariationSink : public gls::ScaleSampleSink
{
public:
  VariationSink(std::size_t n, const std::vector<double>& scales, int threads, bool storeKappa)
    : Scales(scales)
    , Nu(new double[n * scales.size()]) // not zeroed: the threads first-touch their own rows, as in the filters
    , Kappa(storeKappa ? new double[n * scales.size()] : nullptr)
    , Size(n * scales.size())
    , Visits(static_cast<std::size_t>(threads), 0.0)
  {
  }
  void consume(std::uint64_t id, const gls::ScaleSample* s, int thread) override
  {
    const std::size_t S = this->Scales.size();
    for (std::size_t k = 0; k < S; ++k)
    {
      this->Nu[id * S + k] = gls::geometricVariation(s[k], this->Scales[k], {});
    }
    if (this->Kappa)
    {
      for (std::size_t k = 0; k < S; ++k)
      {
        this->Kappa[id * S + k] = s[k].kappa;
      }
    }
    this->Visits[static_cast<std::size_t>(thread)] += s[S - 1].neighbors;
  }
  double visits() const
  {
    double v = 0;
    for (double x : this->Visits)
    {
      v += x;
    }
    return v;
  }
  const std::vector<double>& Scales;
  std::unique_ptr<double[]> Nu, Kappa;
  std::size_t Size;
  std::vector<double> Visits;
};

struct Measure
{
  double seconds = 0, utilisation = 0, visits = 0;
};

/// CPU time (all threads) of a measured run: a ratio of CPU times is less disturbed by other load than wall times.
double cpuSecondsOf(const Measure& m)
{
  return std::max(m.seconds * m.utilisation, 1e-9);
}

Measure scaleSpaceAndNu(const Cloud& c, const std::vector<double>& scales, int threads, gls::EvaluationMethod method,
  std::vector<double>* nu = nullptr, std::vector<double>* kappa = nullptr, bool principalCurvatures = false,
  gls::Evaluation evaluation = gls::Evaluation::Exact)
{
  gls::ScaleSpaceSettings settings;
  settings.scales = scales;
  settings.parallel.threads = threads;
  settings.method = method;
  settings.principalCurvatures = principalCurvatures;
  settings.evaluation = evaluation;
  Timer t;
  gls::ScaleSpaceEngine engine(c.xyz.data(), c.normals.data(), c.size(), settings);
  VariationSink sink(c.size(), scales, gls::resolveThreadCount(threads), kappa != nullptr);
  engine.run(sink);
  Measure m{ t.seconds(), t.utilisation(), sink.visits() };
  if (nu)
  {
    nu->assign(sink.Nu.get(), sink.Nu.get() + sink.Size);
  }
  if (kappa)
  {
    kappa->assign(sink.Kappa.get(), sink.Kappa.get() + sink.Size);
  }
  return m;
}

void row(const char* name, double n, double S, const Measure& m)
{
  std::printf("| %-44s | %9.3f s | %10.2f M | %9.1f M | %5.0f%% | %7.0f MiB |\n", name, m.seconds,
    n * S / m.seconds / 1e6, m.visits / m.seconds / 1e6, 100 * m.utilisation, peakMiB());
  std::fflush(stdout);
}

void header()
{
  std::printf("| %-44s | %11s | %12s | %11s | %6s | %11s |\n", "case", "wall", "pt-scales/s", "visits/s", "CPU",
    "peak mem");
  std::printf("|%s|%s|%s|%s|%s|%s|\n", std::string(46, '-').c_str(), std::string(13, '-').c_str(),
    std::string(14, '-').c_str(), std::string(13, '-').c_str(), std::string(8, '-').c_str(),
    std::string(13, '-').c_str());
}

/// The tuples of a 3-component array, interleaved.
std::vector<double> tuples(vtkDataArray* a)
{
  std::vector<double> v(3 * static_cast<std::size_t>(a->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    a->GetTuple(i, &v[3 * i]);
  }
  return v;
}

/// How two sets of unit normals (interleaved, same points) agree up to sign: the largest 1 - |u . v| and the number
/// of points where it is above 1e-9.
struct NormalAgreement
{
  double worst = 0.0;
  long long above = 0;
};

NormalAgreement agreement(const std::vector<double>& u, const std::vector<double>& v)
{
  NormalAgreement r;
  for (std::size_t i = 0; i < u.size(); i += 3)
  {
    const double gap = 1.0 - std::abs(u[i] * v[i] + u[i + 1] * v[i + 1] + u[i + 2] * v[i + 2]);
    r.worst = std::max(r.worst, gap);
    r.above += gap > 1e-9 ? 1 : 0;
  }
  return r;
}

/// 1 - |n . ref| for a normal n against a long-double reference, the product taken in long double.
double gapToReference(const double* n, const Eigen::Matrix<long double, 3, 1>& ref)
{
  return 1.0 - std::abs(static_cast<double>(n[0] * ref(0) + n[1] * ref(1) + n[2] * ref(2)));
}

std::vector<double> relativeScales(const Cloud& c, int S, gls::ScaleSampling sampling)
{
  return gls::sampleScales(0.008 * c.diagonal, 0.08 * c.diagonal, S, sampling);
}

void printAngles(const char* what, const AngleAgreement& a)
{
  std::printf("%s: angle between the normals (up to sign) p50 %.2g, p90 %.2g, p99 %.2g, max %.3g degrees; "
              "above 1 degree at %lld of %lld points\n",
    what, a.p50, a.p90, a.p99, a.max, a.aboveOneDegree, a.compared);
}

/// P1's CloudCompare column: -CURV MEAN r at the 20 scales on the same cloud, timed against GLS's one pass (which
/// computes the whole scale space and nu), and its |H| against GLS |kappa| scale by scale.
void cloudCompareCurvatureColumn(const Cloud& c, const std::vector<double>& scales, const std::vector<double>& kappa,
  const Measure& gls, int threads)
{
  const double unitScale = 1000.0; // see cloudCompareMeanCurvature: its fit fails at small kernels in small units
  const CloudCompareResult cc = cloudCompareMeanCurvature(c.xyz, scales, threads, unitScale);
  if (!cc.ok)
  {
    std::printf("P1: CloudCompare column skipped: %s\n", cc.message.c_str());
    return;
  }
  std::printf("P1: CloudCompare -CURV MEAN r at the %zu scales, %d cores allowed (%d threads busy): compute %.2f s "
              "(CPU %.0f%%), "
              "start-up + import %.2f s, export %.2f s (the .xyz written by us in %.2f s); compute / GLS one pass "
              "= %.1fx wall, %.1fx CPU time\n",
    scales.size(), threads, cc.computeThreads, cc.computeSeconds,
    100.0 * cc.computeCpuSeconds / std::max(cc.computeSeconds, 1e-9), cc.importSeconds, cc.exportSeconds,
    cc.writeInputSeconds, cc.computeSeconds / gls.seconds,
    cc.computeCpuSeconds / cpuSecondsOf(gls));
  std::printf("P1: CloudCompare |H| (|k1 + k2| / 2 of its quadric, unsigned; given the cloud x %g and |H| "
              "multiplied back) against GLS |kappa| (1 / the fitted sphere's radius) at the same radius, 1/length, "
              "no other conversion:\n", unitScale);
  std::printf("| %8s | %6s | %8s | %14s | %12s | %13s | %7s | %8s |\n", "t", "t/diag", "points", "median |kappa|",
    "median |H|", "median |H|/|k|", "Pearson", "Spearman");
  const std::size_t S = scales.size();
  std::vector<double> absKappa(kappa.size());
  std::transform(kappa.begin(), kappa.end(), absKappa.begin(), [](double k) { return std::abs(k); });
  for (std::size_t k = 0; k < S; ++k)
  {
    const CurvatureAgreement a = curvatureAgreement(absKappa.data() + k, cc.columns.data() + k, c.size(), S);
    std::printf("| %8.5f | %6.4f | %8lld | %14.4g | %12.4g | %13.3f | %7.3f | %8.3f |\n", scales[k],
      scales[k] / c.diagonal, a.compared, a.medianGls, a.medianPeer, a.medianRatio, a.pearson, a.spearman);
  }
}

} // namespace

int main(int argc, char* argv[])
{
  std::string which = "all";
  int threads = 0;
  bool peers = true;
  int repeats = 2;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--case") && i + 1 < argc)
    {
      which = argv[++i];
    }
    else if (!std::strcmp(argv[i], "--no-peers"))
    {
      peers = false;
    }
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc)
    {
      threads = std::atoi(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc && std::atoi(argv[i + 1]) > 0)
    {
      repeats = std::atoi(argv[++i]);
    }
    else
    {
      std::fprintf(stderr,
        "usage: %s [--case all|P1|P2|P3|P4|P5|P1-one-pass|C1|C1-multiresolution] [--threads T] [--no-peers] "
        "[--repeats R]\n",
        argv[0]);
      return 2;
    }
  }
  const bool all = which == "all";
  const int peerThreads = gls::resolveThreadCount(threads); // the peers get GLS's thread count
  std::printf("threads: %d; one-pass CPU kernel build: %s\n", peerThreads, gls::onePassKernelBuild());
  std::map<std::string, double> seconds;

  if (all || which == "C1" || which == "C1-multiresolution")
  {
    const Cloud c = bunny(173000);
    const auto scales = relativeScales(c, 20, gls::ScaleSampling::Quadratic);
    header();
    for (const gls::Evaluation evaluation : { gls::Evaluation::Exact, gls::Evaluation::Multiresolution })
    {
      const bool cells = evaluation == gls::Evaluation::Multiresolution;
      if (!cells && which == "C1-multiresolution")
      {
        continue;
      }
      double alone = 0.0, with = 0.0, fastestAlone = 1e300, fastestWith = 1e300;
      for (int repeat = 0; repeat < repeats; ++repeat)
      {
        const auto one = gls::EvaluationMethod::OnePass;
        const Measure a = scaleSpaceAndNu(c, scales, threads, one, nullptr, nullptr, false, evaluation);
        row(cells ? "C1 multi-resolution, scale space alone" : "C1 exact, scale space alone", 173000, 20, a);
        const Measure w = scaleSpaceAndNu(c, scales, threads, one, nullptr, nullptr, true, evaluation);
        row(cells ? "C1 multi-resolution, with the curvatures" : "C1 exact, with the curvatures", 173000, 20, w);
        alone += cpuSecondsOf(a);
        with += cpuSecondsOf(w);
        fastestAlone = std::min(fastestAlone, cpuSecondsOf(a));
        fastestWith = std::min(fastestWith, cpuSecondsOf(w));
      }
      std::printf("C1 %s: principal curvatures / scale space alone = %.2fx (CPU time, %d runs each; fastest runs "
                  "%.2fx)\n",
        cells ? "multi-resolution" : "exact", with / alone, repeats, fastestWith / fastestAlone);
    }
  }
  if (all || which == "P1" || which == "P2" || which == "P3" || which == "P1-one-pass")
  {
    const Cloud c = bunny(173000);
    const auto scales = relativeScales(c, 20, gls::ScaleSampling::Quadratic);
    header();
    std::vector<double> nuMany, nuOne, kappa;
    const Measure p1 = scaleSpaceAndNu(c, scales, threads, gls::EvaluationMethod::OnePass, &nuMany, &kappa);
    row("P1 173k x 20 scales, one pass", 173000, 20, p1);
    seconds["P1"] = p1.seconds;
    if (all || which == "P1")
    {
      const Measure base = scaleSpaceAndNu(c, scales, threads, gls::EvaluationMethod::PerScale);
      row("P1 baseline: per-scale query + fit", 173000, 20, base);
      const Measure single = scaleSpaceAndNu(c, scales, 1, gls::EvaluationMethod::OnePass, &nuOne);
      row("P1 one pass, 1 thread", 173000, 20, single);
      std::printf("P1: per-scale / one-pass = %.1fx; 1 thread / all = %.2fx; results bitwise identical to the "
                  "1-thread run: %s\n",
        base.seconds / p1.seconds, single.seconds / p1.seconds,
        std::memcmp(nuMany.data(), nuOne.data(), nuOne.size() * sizeof(double)) == 0 ? "yes" : "NO");
      if (peers)
      {
        cloudCompareCurvatureColumn(c, scales, kappa, p1, peerThreads);
      }
    }
    if (all || which == "P2")
    {
      const auto many = relativeScales(c, 1000, gls::ScaleSampling::Quadratic);
      const Measure p2 = scaleSpaceAndNu(c, many, threads, gls::EvaluationMethod::OnePass);
      row("P2 173k x 1000 scales, one pass", 173000, 1000, p2);
      std::printf("P2 / P1 = %.2fx (target <= 3)\n", p2.seconds / p1.seconds);
    }
    if (all || which == "P3")
    {
      const Cloud big = bunny(1000000);
      const Measure p3 = scaleSpaceAndNu(big, relativeScales(big, 20, gls::ScaleSampling::Quadratic), threads,
        gls::EvaluationMethod::OnePass);
      row("P3 1M x 20 scales, one pass", 1e6, 20, p3);
      std::printf("P3 / P1 = %.2fx (target <= 7; neighbours per ball grow %.1fx with the density)\n",
        p3.seconds / p1.seconds, (p3.visits / 1e6) / (p1.visits / 173000));
    }
  }

  if (all || which == "P4")
  {
    const Cloud c = bunny(1000000);
    vtkNew<vtkPolyData> pd;
    {
      auto sampled = sampleMeshSurface(GLS_BENCHMARK_MODEL, 1000000, 1);
      pd->SetPoints(sampled->GetPoints());
    }
    // A radius holding about 30 neighbours: 30 = density * pi r^2, density from the mean k = 16 radius.
    double area = 0.0;
    gls::NeighborGrid grid;
    grid.build(c.xyz.data(), nullptr, c.size(), gls::NeighborGrid::suggestCellSizeForKNearest(c.xyz.data(), c.size(), 16));
    {
      // Mean squared distance to the 16th neighbour on a sample of points gives the local density.
      std::vector<std::pair<double, std::uint64_t>> knn;
      for (std::size_t i = 0; i < c.size(); i += 1000)
      {
        grid.kNearest({ c.xyz[3 * i], c.xyz[3 * i + 1], c.xyz[3 * i + 2] }, 16, knn);
        area += knn.back().first;
      }
      area /= static_cast<double>((c.size() + 999) / 1000);
    }
    const double radius = std::sqrt(area * 30.0 / 16.0);
    header();
    Timer t;
    vtkNew<vtkGLSNormalEstimation> ours;
    ours->SetInputData(pd);
    ours->SetOrientationToNone();
    ours->SetNumberOfThreads(threads);
    ours->Update();
    Measure m{ t.seconds(), t.utilisation(), 16e6 };
    row("P4 normals 1M, k = 16 (GLS)", 1e6, 1, m);
    vtkSMPTools::SetBackend("STDThread");
    if (threads > 0)
    {
      vtkSMPTools::Initialize(threads);
    }
    Timer tv;
    vtkNew<vtkPCANormalEstimation> vtk;
    vtk->SetInputData(pd);
    vtk->SetSampleSize(16);
    vtk->SetNormalOrientationToAsComputed();
    vtk->Update();
    Measure mv{ tv.seconds(), tv.utilisation(), 16e6 };
    row("P4 vtkPCANormalEstimation k = 16 (STDThread)", 1e6, 1, mv);
    const std::vector<double> glsNormals = tuples(ours->GetOutput()->GetPointData()->GetNormals());
    const std::vector<double> vtkNormals = tuples(vtk->GetOutput()->GetPointData()->GetNormals());
    const NormalAgreement withVtk = agreement(glsNormals, vtkNormals);
    std::printf("P4: vtkPCANormalEstimation / GLS = %.2fx (target >= 2); 1 - |n_gls . n_vtk|: max %.2e, above 1e-9 "
                "at %lld of %lld points\n",
      mv.seconds / m.seconds, withVtk.worst, withVtk.above, static_cast<long long>(glsNormals.size() / 3));
    // Open3D: the 16 nearest within the ~30-neighbour radius (the radius bounds the search; nearly every point has
    // 16 neighbours inside it, so this is k = 16 as GLS's).
    Open3DResult open3d;
    open3d.message = "--no-peers";
    if (peers)
    {
      open3d = open3dNormals(c.xyz, radius, 16, peerThreads);
    }
    if (open3d.ok)
    {
      std::printf("P4: Open3D %s estimate_normals(KDTreeSearchParamHybrid(radius %.4g, max_nn 16)), %d OpenMP "
                  "threads (%d busy): compute %.2f s (CPU %.0f%%), whole process %.2f s (start-up, raw-double I/O); "
                  "compute / GLS = %.2fx wall, %.2fx CPU time\n",
        open3d.version.c_str(), radius, peerThreads, open3d.computeThreads, open3d.computeSeconds,
        100.0 * open3d.computeCpuSeconds / std::max(open3d.computeSeconds, 1e-9), open3d.processSeconds,
        open3d.computeSeconds / m.seconds, open3d.computeCpuSeconds / cpuSecondsOf(m));
      printAngles("P4: Open3D against GLS k = 16", angleAgreement(open3d.normals, glsNormals));
      // Where they differ: does the radius cut Open3D's search short of 16 neighbours there?
      const std::vector<std::size_t> apart = pointsApartBy(open3d.normals, glsNormals, 1.0);
      std::size_t cut = 0;
      std::vector<std::pair<double, std::uint64_t>> knn;
      for (std::size_t i : apart)
      {
        grid.kNearest({ c.xyz[3 * i], c.xyz[3 * i + 1], c.xyz[3 * i + 2] }, 16, knn);
        cut += knn.back().first > radius * radius ? 1 : 0;
      }
      std::printf("P4: of the %zu points more than 1 degree apart, %zu have fewer than 16 neighbours within the "
                  "radius (Open3D fits those, GLS the 16 nearest)\n",
        apart.size(), cut);
    }
    else
    {
      std::printf("P4: Open3D column skipped: %s\n", open3d.message.c_str());
    }
    std::vector<double> cgal; // CGAL's normals, when the optional column is built
#ifdef GLS_BENCHMARK_WITH_CGAL
    {
      Timer tc;
      cgalPcaNormals(c.xyz, 16, threads, cgal);
      Measure mc{ tc.seconds(), tc.utilisation(), 16e6 };
      row("P4 CGAL pca_estimate_normals k = 16 (TBB)", 1e6, 1, mc);
      const NormalAgreement withCgal = agreement(glsNormals, cgal);
      std::printf("P4: CGAL / GLS = %.2fx; 1 - |n_gls . n_cgal|: max %.2e, above 1e-9 at %lld points\n",
        mc.seconds / m.seconds, withCgal.worst, withCgal.above);
    }
#endif
    // Who is right where they differ: a third computation in long double (brute-force 16 nearest, Eigen's
    // symmetric eigensolver) on 500 points.
    {
      double worstOurs = 0.0, worstVtk = 0.0, worstCgal = 0.0, worstOpen3d = 0.0, worstOpen3dFull = 0.0;
      std::vector<std::pair<double, std::size_t>> all(c.size());
      for (std::size_t q = 0; q < c.size(); q += c.size() / 500)
      {
        for (std::size_t i = 0; i < c.size(); ++i)
        {
          double d2 = 0;
          for (int k = 0; k < 3; ++k)
          {
            d2 += (c.xyz[3 * i + k] - c.xyz[3 * q + k]) * (c.xyz[3 * i + k] - c.xyz[3 * q + k]);
          }
          all[i] = { d2, i };
        }
        std::partial_sort(all.begin(), all.begin() + 16, all.end());
        Eigen::Matrix<long double, 3, 1> mean = Eigen::Matrix<long double, 3, 1>::Zero();
        for (int j = 0; j < 16; ++j)
        {
          for (int k = 0; k < 3; ++k)
          {
            mean(k) += static_cast<long double>(c.xyz[3 * all[j].second + k]) - c.xyz[3 * q + k];
          }
        }
        mean /= 16.0L;
        Eigen::Matrix<long double, 3, 3> cov = Eigen::Matrix<long double, 3, 3>::Zero();
        for (int j = 0; j < 16; ++j)
        {
          Eigen::Matrix<long double, 3, 1> d;
          for (int k = 0; k < 3; ++k)
          {
            d(k) = static_cast<long double>(c.xyz[3 * all[j].second + k]) - c.xyz[3 * q + k] - mean(k);
          }
          cov += d * d.transpose();
        }
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix<long double, 3, 3>> solver(cov);
        const Eigen::Matrix<long double, 3, 1> ref = solver.eigenvectors().col(0).normalized();
        worstOurs = std::max(worstOurs, gapToReference(&glsNormals[3 * q], ref));
        worstVtk = std::max(worstVtk, gapToReference(&vtkNormals[3 * q], ref));
        if (!cgal.empty())
        {
          worstCgal = std::max(worstCgal, gapToReference(&cgal[3 * q], ref));
        }
        if (open3d.ok)
        {
          const double gap = gapToReference(&open3d.normals[3 * q], ref);
          worstOpen3d = std::max(worstOpen3d, gap);
          if (all[15].first <= radius * radius) // its search radius holds the 16 nearest: the same neighbours
          {
            worstOpen3dFull = std::max(worstOpen3dFull, gap);
          }
        }
      }
      std::printf("P4: against a long-double reference on 500 points, max 1 - |n . n_ref|: GLS %.2e, VTK %.2e",
        worstOurs, worstVtk);
      if (!cgal.empty())
      {
        std::printf(", CGAL %.2e", worstCgal);
      }
      if (open3d.ok)
      {
        std::printf(", Open3D %.2e (%.2e where its radius holds the 16 nearest)", worstOpen3d, worstOpen3dFull);
      }
      std::printf("\n");
    }
    Timer tr;
    vtkNew<vtkGLSNormalEstimation> byRadius;
    byRadius->SetInputData(pd);
    byRadius->SetNeighborhoodTypeToRadius();
    byRadius->SetRadius(radius);
    byRadius->SetOrientationToNone();
    byRadius->SetNumberOfThreads(threads);
    byRadius->Update();
    Measure mr{ tr.seconds(), tr.utilisation(), 30e6 };
    row("P4 normals 1M, radius (~30 neighbours, GLS)", 1e6, 1, mr);
    CloudCompareResult cc;
    cc.message = "--no-peers";
    if (peers)
    {
      cc = cloudCompareOctreeNormals(c.xyz, radius, peerThreads);
    }
    if (cc.ok)
    {
      std::printf("P4: CloudCompare -OCTREE_NORMALS %.4g -MODEL LS, %d cores allowed (%d threads busy): compute %.2f s "
                  "(CPU %.0f%%), "
                  "start-up + import %.2f s, export %.2f s (the .xyz written by us in %.2f s); compute / GLS radius "
                  "= %.2fx wall, %.2fx CPU time\n",
        radius, peerThreads, cc.computeThreads, cc.computeSeconds,
        100.0 * cc.computeCpuSeconds / std::max(cc.computeSeconds, 1e-9),
        cc.importSeconds, cc.exportSeconds, cc.writeInputSeconds, cc.computeSeconds / mr.seconds,
        cc.computeCpuSeconds / cpuSecondsOf(mr));
      printAngles("P4: CloudCompare against GLS over the same radius",
        angleAgreement(cc.columns, tuples(byRadius->GetOutput()->GetPointData()->GetNormals())));
    }
    else
    {
      std::printf("P4: CloudCompare column skipped: %s\n", cc.message.c_str());
    }
  }

  if (which == "P5")
  {
    const Cloud c = bunny(1000000);
    vtkNew<vtkPolyData> pd;
    {
      auto sampled = sampleMeshSurface(GLS_BENCHMARK_MODEL, 1000000, 1);
      pd->SetPoints(sampled->GetPoints());
      pd->GetPointData()->SetNormals(sampled->GetPointData()->GetNormals());
    }
    const double before = peakMiB();
    header();
    Timer t;
    vtkNew<vtkGLSContinuousFeatures> features;
    features->SetInputData(pd);
    features->SetNumberOfScales(100);
    features->SetMinScale(0.0008); // 0.08% to 0.8% of the diagonal: about 300 neighbours at the largest scale
    features->SetMaxScale(0.008);
    features->SetNumberOfThreads(threads);
    features->Update();
    Measure m{ t.seconds(), t.utilisation(), 0.0 };
    row("P5 fused features 1M x 100 scales", 1e6, 100, m);
    std::printf("P5: peak memory %.0f MiB for the whole process (%.0f MiB before the filter; target < 1024)\n",
      peakMiB(), before);
  }
  return 0;
}
