// Normals under scanner sampling (issue "Normals that survive real scanner sampling"): the bundled meshes scanned by
// a simulated scanner (ScannerSimulation.h: two positions, 10:1 denser along the scan lines than across, first
// hits), the estimated normals against the hit triangles' normals; then the time of the estimate on 1M points.
//
//   glsNormalsBenchmark [--models bunny,spot,...] [--samples-along N] [--anisotropy A] [--subdivide L]
//                       [--invariance 0|1] [--noisy-points N] [--timing-points N] [--threads T]
//
// --samples-along: rays per scan line (1200); --anisotropy: the spacing across the lines over the spacing along (10);
// --subdivide: Loop subdivision levels applied to the smooth models (not the CAD parts) before the scan (0), so that
// the truth is a smooth surface rather than facets larger than the scan's spacing.
//
// Per model and method: percentiles of the angle to the true normal (unoriented, degrees), the share within 5
// degrees (of the hit triangle's normal, and of the mesh's smooth normal there), the share pointing the wrong way (oriented dot < 0, among the defined normals) and the share of NaN. The
// true normal is the hit triangle's turned towards the scanner (the side a first hit sees); the wrong way is counted
// against it and against the file's winding (outward on a closed, consistently wound mesh): the two differ where a
// scanner sees the back of a surface through an opening (the bunny's holes, the open side of fandisk), where no
// consistent orientation can face both scanners.
// On the CAD parts (fandisk, rocker arm) only the points farther than 1% of the diagonal from a crease (dihedral
// above 30 degrees) count. Methods: GLS with its defaults; GLS without growth (MaximumGrowth 1, MinimumSpread 0:
// the estimate before adaptive neighbourhoods); GLS oriented towards the per-point ScannerPosition array
// (TOWARDS_VIEWPOINT_ARRAY); GLS refined; and, as a reference for what "within 5 degrees" can mean on these meshes, the
// mesh's own vertex normals interpolated at the hits (a smooth surface against its facets);
// vtkPCANormalEstimation (k = 16, graph-traversal orientation).
#include "CommaList.h"
#include "MeshSampler.h"
#include "ScannerSimulation.h"

#include "vtkGLSContinuousFeatures.h"
#include "vtkGLSNormalEstimation.h"

#include "vtkCleanPolyData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkLoopSubdivisionFilter.h"
#include "vtkStaticPointLocator.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPCANormalEstimation.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{

constexpr double kDegree = 3.14159265358979323846 / 180.0;

struct Method
{
  const char* Name;
  std::function<vtkSmartPointer<vtkPolyData>(vtkPolyData*)> Run;
};

vtkSmartPointer<vtkPolyData> keep(vtkDataObject* o)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(o);
  return out;
}

vtkSmartPointer<vtkPolyData> glsNormals(vtkPolyData* in, int threads, const std::function<void(vtkGLSNormalEstimation*)>& set)
{
  vtkNew<vtkGLSNormalEstimation> f;
  f->SetInputData(in);
  f->SetNumberOfThreads(threads);
  set(f);
  f->Update();
  return keep(f->GetOutput());
}

double percentile(std::vector<double> v, double q)
{
  if (v.empty())
  {
    return std::nan("");
  }
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

/// One row of the table: the estimated normals of `out` against the scan's true normals, on the counted points.
void report(const char* model, const char* method, vtkPolyData* out, const ScannerScan& scan,
  const std::vector<unsigned char>& counted, double seconds)
{
  vtkDataArray* n = out->GetPointData()->GetNormals();
  std::vector<double> angles;
  std::size_t total = 0, nan = 0, wrong = 0, unwound = 0, within5 = 0, smooth5 = 0;
  for (std::size_t i = 0; i < scan.Size(); ++i)
  {
    if (!counted[i])
    {
      continue;
    }
    ++total;
    double v[3];
    n->GetTuple(static_cast<vtkIdType>(i), v);
    const double* t = &scan.Normals[3 * i];
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(length > 0.0) || !std::isfinite(length))
    {
      ++nan;
      angles.push_back(180.0); // a missing normal counts as not within 5 degrees
      continue;
    }
    const double c = (v[0] * t[0] + v[1] * t[1] + v[2] * t[2]) / length;
    wrong += c < 0.0 ? 1 : 0;
    const double* sm = &scan.SmoothNormals[3 * i];
    smooth5 += std::abs(v[0] * sm[0] + v[1] * sm[1] + v[2] * sm[2]) / length >= std::cos(5.0 * kDegree) ? 1 : 0;
    const double* w = &scan.WoundNormals[3 * i];
    unwound += v[0] * w[0] + v[1] * w[1] + v[2] * w[2] < 0.0 ? 1 : 0;
    const double a = std::acos(std::min(1.0, std::abs(c))) / kDegree;
    within5 += a <= 5.0 ? 1 : 0;
    angles.push_back(a);
  }
  const double defined = static_cast<double>(total - nan);
  std::printf(
    "| %-12s | %-34s | %7zu | %6.2f | %6.2f | %6.2f | %6.2f | %6.1f%% | %6.1f%% | %6.2f%% | %6.2f%% | %5.2f%% | %6.2f |\n",
    model, method, total, percentile(angles, 0.5), percentile(angles, 0.9), percentile(angles, 0.95),
    percentile(angles, 0.99), 100.0 * within5 / std::max<double>(1.0, static_cast<double>(total)),
    100.0 * smooth5 / std::max<double>(1.0, static_cast<double>(total)),
    100.0 * wrong / std::max(1.0, defined), 100.0 * unwound / std::max(1.0, defined),
    100.0 * nan / std::max<double>(1.0, static_cast<double>(total)), seconds);
  std::fflush(stdout);
}

} // namespace

int main(int argc, char* argv[])
{
  std::string models = "stanford-bunny,spot,cheburashka,fandisk,rocker-arm";
  int samplesAlong = 1200;
  long long timingPoints = 1000000;
  long long noisyPoints = 200000;
  bool invariance = true;
  int threads = 0;
  int subdivide = 0;
  double anisotropy = 10.0;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    if (!std::strcmp(argv[i], "--models"))
      models = argv[i + 1];
    else if (!std::strcmp(argv[i], "--samples-along"))
      samplesAlong = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--invariance"))
      invariance = std::atoi(argv[i + 1]) != 0;
    else if (!std::strcmp(argv[i], "--noisy-points"))
      noisyPoints = std::atoll(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--timing-points"))
      timingPoints = std::atoll(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--threads"))
      threads = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--anisotropy"))
      anisotropy = std::atof(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--subdivide"))
      subdivide = std::atoi(argv[i + 1]);
    else
    {
      std::fprintf(stderr,
        "usage: %s [--models a,b] [--samples-along N] [--anisotropy A] [--subdivide L] [--invariance 0|1] "
        "[--noisy-points N] [--timing-points N] [--threads T]\n",
        argv[0]);
      return 2;
    }
  }
  vtkSMPTools::SetBackend("STDThread");
  if (threads > 0)
  {
    vtkSMPTools::Initialize(threads);
  }
  using Clock = std::chrono::steady_clock;
  const std::vector<Method> methods = {
    { "GLS defaults", [threads](vtkPolyData* in) { return glsNormals(in, threads, [](vtkGLSNormalEstimation*) {}); } },
    { "GLS without growth (before)",
      [threads](vtkPolyData* in) {
        return glsNormals(in, threads, [](vtkGLSNormalEstimation* f) {
          f->SetMaximumGrowth(1.0);
          f->SetMinimumSpread(0.0);
        });
      } },
    { "GLS towards ScannerPosition",
      [threads](vtkPolyData* in) {
        return glsNormals(in, threads, [](vtkGLSNormalEstimation* f) {
          f->SetOrientationToTowardsViewpointArray();
          f->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "ScannerPosition");
        });
      } },
    { "GLS + GLS refinement (1.5)",
      [threads](vtkPolyData* in) {
        return glsNormals(in, threads, [](vtkGLSNormalEstimation* f) { f->SetRefinementToGLS(); });
      } },
    { "GLS + GLS refinement (2.5)",
      [threads](vtkPolyData* in) {
        return glsNormals(in, threads, [](vtkGLSNormalEstimation* f) {
          f->SetRefinementToGLS();
          f->SetRefinementScale(2.5);
        });
      } },
    { "vtkPCANormalEstimation k 16, graph",
      [](vtkPolyData* in) {
        vtkNew<vtkPCANormalEstimation> f;
        f->SetInputData(in);
        f->SetSampleSize(16);
        f->SetNormalOrientationToGraphTraversal();
        f->Update();
        return keep(f->GetOutput());
      } },
  };

  std::printf("Scanner simulation: two positions, %d rays per scan line, %g:1 denser along the lines than across, "
              "smooth models Loop-subdivided %d times\n",
    samplesAlong, anisotropy, subdivide);
  std::printf("| model        | method                             |  points |    p50 |    p90 |    p95 |    p99 | "
              "<= 5 deg | <= 5 deg of smooth | wrong way (scanner side) | wrong way (file winding) |   NaN |      s |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& model : splitCommaList(models))
  {
    vtkNew<vtkOBJReader> reader;
    reader->SetFileName((std::string(GLS_BENCHMARK_DATA_DIR) + "/" + model + ".obj").c_str());
    vtkNew<vtkCleanPolyData> clean; // per-corner vertex copies (texture coordinates) merged
    clean->SetInputConnection(reader->GetOutputPort());
    clean->SetTolerance(0.0);
    clean->Update();
    vtkSmartPointer<vtkPolyData> mesh = clean->GetOutput();
    const bool cad = model == "fandisk" || model == "rocker-arm";
    if (subdivide > 0 && !cad)
    {
      vtkNew<vtkLoopSubdivisionFilter> loop;
      loop->SetInputData(mesh);
      loop->SetNumberOfSubdivisions(subdivide);
      loop->Update();
      mesh = loop->GetOutput();
    }
    if (mesh->GetNumberOfCells() == 0)
    {
      std::printf("| %s | cannot read the mesh |\n", model.c_str());
      continue;
    }
    ScannerSettings settings;
    settings.SamplesAlong = samplesAlong;
    settings.Anisotropy = anisotropy;
    const ScannerScan scan = simulateScanner(mesh, settings);
    std::vector<unsigned char> counted(scan.Size(), 1);
    if (cad)
    {
      const std::vector<double> d = distanceToCreases(mesh, scan, 30.0);
      for (std::size_t i = 0; i < scan.Size(); ++i)
      {
        counted[i] = d[i] > 0.01 * mesh->GetLength() ? 1 : 0;
      }
    }
    std::printf("| %-12s | (%zu hits; the file winds %.2f%% of the hit triangles away from the scanner: turned) "
                "| | | | | | | | | | | |\n",
      model.c_str(), scan.Size(), 100.0 * scan.FlippedTriangles / std::max<double>(1.0, static_cast<double>(scan.Size())));
    vtkSmartPointer<vtkPolyData> input = scanAsPolyData(scan);
    {
      // A reference row: the mesh's own smooth normals (vertex normals interpolated at the hits) against the facets.
      auto smooth = vtkSmartPointer<vtkPolyData>::New();
      smooth->ShallowCopy(input);
      vtkNew<vtkDoubleArray> normals;
      normals->SetNumberOfComponents(3);
      normals->SetNumberOfTuples(static_cast<vtkIdType>(scan.Size()));
      for (std::size_t i = 0; i < scan.Size(); ++i)
      {
        normals->SetTuple(static_cast<vtkIdType>(i), &scan.SmoothNormals[3 * i]);
      }
      smooth->GetPointData()->SetNormals(normals);
      report(model.c_str(), "(mesh vertex normals, interpolated)", smooth, scan, counted, 0.0);
    }
    for (const Method& m : methods)
    {
      const Clock::time_point t0 = Clock::now();
      vtkSmartPointer<vtkPolyData> out = m.Run(input);
      const double s = std::chrono::duration<double>(Clock::now() - t0).count();
      report(model.c_str(), m.Name, out, scan, counted, s);
    }
  }

  if (invariance)
  {
    // Sampling invariance of the whole pipeline (features at the default scales and sigma): the bunny sampled by area
    // and scanned, each with its true normals and with the default estimated ones; each scan point against its
    // nearest area sample.
    vtkNew<vtkOBJReader> reader;
    reader->SetFileName((std::string(GLS_BENCHMARK_DATA_DIR) + "/stanford-bunny.obj").c_str());
    reader->Update();
    ScannerSettings settings;
    settings.SamplesAlong = samplesAlong;
    const ScannerScan scan = simulateScanner(reader->GetOutput(), settings);
    vtkSmartPointer<vtkPolyData> area = sampleMeshSurface(
      std::string(GLS_BENCHMARK_DATA_DIR) + "/stanford-bunny.obj", static_cast<std::int64_t>(scan.Size()), 5);
    vtkSmartPointer<vtkPolyData> scanned = scanAsPolyData(scan);
    vtkNew<vtkDoubleArray> trueScanNormals;
    trueScanNormals->DeepCopy(scanned->GetPointData()->GetArray("TrueNormals"));
    trueScanNormals->SetName("Normals");
    auto features = [threads](vtkPolyData* in, bool estimate) {
      vtkNew<vtkGLSContinuousFeatures> f;
      f->SetNumberOfThreads(threads);
      f->SetInputData(estimate ? glsNormals(in, threads, [](vtkGLSNormalEstimation*) {}).GetPointer() : in);
      f->Update();
      vtkDataArray* a = f->GetOutput()->GetPointData()->GetArray("GLSFeature");
      std::vector<double> v(static_cast<std::size_t>(a->GetNumberOfTuples()));
      for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
      {
        v[static_cast<std::size_t>(i)] = a->GetComponent(i, 0);
      }
      return v;
    };
    vtkNew<vtkPolyData> areaPoints, scanPoints, scanTrue;
    areaPoints->SetPoints(area->GetPoints());
    scanPoints->SetPoints(scanned->GetPoints());
    scanTrue->SetPoints(scanned->GetPoints());
    scanTrue->GetPointData()->SetNormals(trueScanNormals);
    vtkNew<vtkStaticPointLocator> locator;
    locator->SetDataSet(area);
    locator->BuildLocator();
    std::vector<vtkIdType> match(scan.Size());
    for (std::size_t i = 0; i < scan.Size(); ++i)
    {
      match[i] = locator->FindClosestPoint(&scan.Points[3 * i]);
    }
    const std::vector<double> fAreaTrue = features(area, false), fScanTrue = features(scanTrue, false);
    const std::vector<double> fAreaEst = features(areaPoints, true), fScanEst = features(scanPoints, true);
    std::printf("Sampling invariance (bunny, %zu scanned points against as many area samples, default features):\n",
      scan.Size());
    double p95[2] = { 0, 0 };
    for (int estimated = 0; estimated < 2; ++estimated)
    {
      const std::vector<double>& a = estimated ? fAreaEst : fAreaTrue;
      const std::vector<double>& b = estimated ? fScanEst : fScanTrue;
      std::vector<double> d;
      for (std::size_t i = 0; i < scan.Size(); ++i)
      {
        const double x = b[i] - a[static_cast<std::size_t>(match[i])];
        d.push_back(std::isfinite(x) ? std::abs(x) : 1.0);
      }
      p95[estimated] = percentile(d, 0.95);
      std::printf("  %-28s |f_scan - f_area|: p50 %.3f, p95 %.3f, p99 %.3f\n",
        estimated ? "default estimated normals" : "true (mesh) normals", percentile(d, 0.5), p95[estimated],
        percentile(d, 0.99));
    }
    std::printf("  the estimated normals add %.3f at p95 (target <= 0.02)\n", p95[1] - p95[0]);
  }

  if (noisyPoints > 0)
  {
    // Noisy positions: the bunny sampled to noisyPoints points, moved along their normals by a Gaussian of 0.1% of
    // the diagonal (fixed seed); the mean angle of the estimated normals to the mesh's, with and without refinement.
    vtkSmartPointer<vtkPolyData> sampled =
      sampleMeshSurface(std::string(GLS_BENCHMARK_DATA_DIR) + "/stanford-bunny.obj", noisyPoints, 7);
    vtkDataArray* truth = sampled->GetPointData()->GetNormals();
    const double sigma = 0.001 * sampled->GetLength();
    std::mt19937_64 random(11);
    std::normal_distribution<double> noise(0.0, sigma);
    vtkNew<vtkPoints> moved;
    moved->SetDataTypeToDouble();
    moved->SetNumberOfPoints(sampled->GetNumberOfPoints());
    for (vtkIdType i = 0; i < sampled->GetNumberOfPoints(); ++i)
    {
      double x[3], nrm[3];
      sampled->GetPoint(i, x);
      truth->GetTuple(i, nrm);
      const double e = noise(random);
      moved->SetPoint(i, x[0] + e * nrm[0], x[1] + e * nrm[1], x[2] + e * nrm[2]);
    }
    vtkNew<vtkPolyData> noisy;
    noisy->SetPoints(moved);
    std::printf("Noisy bunny, %lld points, noise 0.1%% of the diagonal along the normals:\n", noisyPoints);
    for (double factor : { 0.0, 1.0, 1.5, 2.5 })
    {
      vtkSmartPointer<vtkPolyData> out = glsNormals(noisy, threads, [factor](vtkGLSNormalEstimation* f) {
        if (factor > 0.0)
        {
          f->SetRefinementToGLS();
          f->SetRefinementScale(factor);
        }
      });
      vtkDataArray* n = out->GetPointData()->GetNormals();
      double sum = 0.0;
      std::vector<double> angles;
      for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
      {
        double a[3], b[3];
        n->GetTuple(i, a);
        truth->GetTuple(i, b);
        const double c = std::abs(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) /
          std::sqrt((a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) * (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]));
        const double angle = std::acos(std::min(1.0, c)) / kDegree;
        sum += std::isfinite(angle) ? angle : 180.0;
        angles.push_back(std::isfinite(angle) ? angle : 180.0);
      }
      std::printf("  %-30s mean angle %.2f degrees, p50 %.2f, p95 %.2f\n",
        factor > 0.0 ? ("GLS refinement, scale " + std::to_string(factor).substr(0, 3)).c_str() : "no refinement",
        sum / static_cast<double>(angles.size()), percentile(angles, 0.5), percentile(angles, 0.95));
    }
  }

  if (timingPoints > 0)
  {
    // The time of the estimate alone (no orientation) on a uniform sample of the bunny, side by side in one run.
    vtkSmartPointer<vtkPolyData> sampled =
      sampleMeshSurface(std::string(GLS_BENCHMARK_DATA_DIR) + "/stanford-bunny.obj", timingPoints, 1);
    vtkNew<vtkPolyData> pd;
    pd->SetPoints(sampled->GetPoints());
    auto time = [](const std::function<void()>& f) {
      const Clock::time_point t0 = Clock::now();
      f();
      return std::chrono::duration<double>(Clock::now() - t0).count();
    };
    const double adaptive = time([&] {
      glsNormals(pd, threads, [](vtkGLSNormalEstimation* f) { f->SetOrientationToNone(); });
    });
    const double before = time([&] {
      glsNormals(pd, threads, [](vtkGLSNormalEstimation* f) {
        f->SetOrientationToNone();
        f->SetMaximumGrowth(1.0);
        f->SetMinimumSpread(0.0);
      });
    });
    const double vtk = time([&] {
      vtkNew<vtkPCANormalEstimation> f;
      f->SetInputData(pd);
      f->SetSampleSize(16);
      f->SetNormalOrientationToAsComputed();
      f->Update();
    });
    std::printf("Timing, %lld points, k = 16, no orientation: GLS adaptive %.2f s, GLS without growth %.2f s "
                "(adaptive / without = %.2fx, target <= 1.5), vtkPCANormalEstimation %.2f s (VTK / GLS adaptive = "
                "%.2fx, target > 1)\n",
      timingPoints, adaptive, before, adaptive / before, vtk, vtk / adaptive);
  }
  std::printf("normals benchmark complete\n");
  return 0;
}
