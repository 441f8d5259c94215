// Denoising benchmark (issue "applications"): GLS projection with the adaptive bandwidth against the best single
// global scale and VTK's vtkPointSmoothingFilter, on
//   1. the paper's Figure 9 case: a wavy closed curve whose quadrants carry noise on positions and normals (A),
//      positions (B), normals (C), nothing (D) -- see Testing/Core/NoisyCurve.h;
//   2. the bundled bunny sampled to --points points, split in four slabs along x with the same four cases, scored
//      against the mesh itself (distance to the closest triangle, angle to its normal).
// Prints, per method and region, the RMS distance to the clean surface (in sample spacings) and the RMS normal
// angle (degrees), the RMS and largest move of clean points far from the noise, the wall time, and the issue's
// acceptance figures with PASS/FAIL.
//
// Scale ranges of the adaptive bandwidth, as its documentation advises: from a few spacings up to about the size of
// the smallest feature to keep (curve: 0.004 to 0.15, a third of the waves' length; bunny: 1 to 5 sample spacings,
// 0.3% to 1.5% of the diagonal at 100,000 points). Raising the bunny's largest scale to 6.6 spacings (2%) makes the
// scan stop at coarse bumps of nu on some points and the adaptive result falls just behind the best global scale
// (0.101 vs 0.100 spacing, measured). The noise is a fixed fraction of the diagonal: with fewer points it is a
// smaller fraction of the spacing, and the figures differ.
//
//   glsDenoisingBenchmark [--points N]      (default 100000)
#include "FilterTestUtilities.h"
#include "MeshSampler.h"
#include "NoisyCurve.h"

#include "vtkGLSAdaptiveBandwidth.h"
#include "vtkGLSProjection.h"

#include "vtkGenericCell.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPointData.h"
#include "vtkPointSmoothingFilter.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStaticCellLocator.h"
#include "vtkTriangle.h"
#include "vtkTriangleFilter.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace
{

double seconds(const std::function<void()>& f)
{
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<double> positions(vtkPointSet* pd)
{
  return glstest::values(pd->GetPoints()->GetData());
}

/// The output's normals, or the input's for a method that does not estimate them.
std::vector<double> normalsOf(vtkPointSet* pd, const std::vector<double>& fallback)
{
  vtkDataArray* a = pd->GetPointData()->GetNormals();
  return a ? glstest::values(a) : fallback;
}

/// Per-region scores: RMS distance, RMS angle, RMS and max move of the clean part far from the noise.
struct Scores
{
  double rms[4], angle[4], total, totalAngle, cleanMoveRms, cleanMove;
};

void printHeader(const char* title, double spacing)
{
  std::printf("\n%s (sample spacing %.3g; distances in spacings, angles in degrees)\n", title, spacing);
  std::printf("%-34s %8s | %-17s %-17s %-17s %-17s | %-15s | %s\n", "method", "time s", "A pos+nrm", "B pos",
    "C nrm", "D clean", "all", "clean far move RMS, max");
}

void printRow(const std::string& name, double time, const Scores& s, double spacing)
{
  std::printf("%-34s %8.3f |", name.c_str(), time);
  for (int r = 0; r < 4; ++r)
  {
    std::printf(" %7.3f %7.2f  ", s.rms[r] / spacing, s.angle[r]);
  }
  std::printf("| %6.3f %7.2f | %.4f %.4f\n", s.total / spacing, s.totalAngle, s.cleanMoveRms / spacing,
    s.cleanMove / spacing);
}

// --- Case 1: the Figure 9 curve -------------------------------------------------------------------------------

Scores scoreCurve(const glstest::NoisyCurve& c, vtkPointSet* out)
{
  const std::vector<double> p = positions(out), n = normalsOf(out, c.Normals);
  const glstest::NoisyCurve::Scores s = c.score(p.data(), n.data());
  Scores r{};
  for (int k = 0; k < 4; ++k)
  {
    r.rms[k] = s.positionRms[k];
    r.angle[k] = s.normalRmsDegrees[k];
  }
  r.total = s.totalPositionRms;
  r.totalAngle = s.totalNormalRmsDegrees;
  r.cleanMoveRms = s.cleanInteriorRmsMove;
  r.cleanMove = s.cleanInteriorMaxMove;
  return r;
}

// --- Case 2: the bunny ----------------------------------------------------------------------------------------

struct Bunny
{
  vtkSmartPointer<vtkPolyData> mesh;
  vtkNew<vtkStaticCellLocator> locator;
  std::vector<double> clean, cleanNormals, points, normals;
  std::vector<int> region;
  std::vector<unsigned char> cleanFar;
  double spacing = 0;

  Scores score(vtkPointSet* out) const
  {
    const std::vector<double> p = positions(out), n = normalsOf(out, this->normals);
    double sum[4] = { 0, 0, 0, 0 }, ang[4] = { 0, 0, 0, 0 };
    std::size_t cnt[4] = { 0, 0, 0, 0 };
    Scores s{};
    double cleanSum = 0;
    std::size_t cleanCount = 0;
    vtkNew<vtkGenericCell> cell;
    for (std::size_t i = 0; i < this->region.size(); ++i)
    {
      double closest[3], d2;
      vtkIdType cellId;
      int subId;
      this->locator->FindClosestPoint(&p[3 * i], closest, cell, cellId, subId, d2);
      double fn[3], v0[3], v1[3], v2[3];
      cell->GetPoints()->GetPoint(0, v0); // GetPoint(i) without a buffer reuses one internal tuple
      cell->GetPoints()->GetPoint(1, v1);
      cell->GetPoints()->GetPoint(2, v2);
      vtkTriangle::ComputeNormal(v0, v1, v2, fn);
      const double* m = &n[3 * i];
      const double len = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
      const double cosine = std::min(1.0, std::abs(m[0] * fn[0] + m[1] * fn[1] + m[2] * fn[2]) / len);
      const double a = std::acos(cosine) * 180.0 / M_PI;
      const int r = this->region[i];
      sum[r] += d2;
      ang[r] += a * a;
      cnt[r] += 1;
      if (this->cleanFar[i])
      {
        const double move = std::sqrt(std::pow(p[3 * i] - this->points[3 * i], 2) +
          std::pow(p[3 * i + 1] - this->points[3 * i + 1], 2) + std::pow(p[3 * i + 2] - this->points[3 * i + 2], 2));
        s.cleanMove = std::max(s.cleanMove, move);
        cleanSum += move * move;
        cleanCount += 1;
      }
    }
    double all = 0, allAngle = 0, total = 0;
    for (int r = 0; r < 4; ++r)
    {
      s.rms[r] = std::sqrt(sum[r] / static_cast<double>(cnt[r]));
      s.angle[r] = std::sqrt(ang[r] / static_cast<double>(cnt[r]));
      all += sum[r];
      allAngle += ang[r];
      total += static_cast<double>(cnt[r]);
    }
    s.total = std::sqrt(all / total);
    s.cleanMoveRms = std::sqrt(cleanSum / static_cast<double>(cleanCount));
    s.totalAngle = std::sqrt(allAngle / total);
    return s;
  }
};

bool makeBunny(Bunny& b, std::int64_t count)
{
  vtkSmartPointer<vtkPolyData> samples = sampleMeshSurface(GLS_BENCHMARK_MODEL, count, 7);
  if (!samples)
  {
    return false;
  }
  vtkNew<vtkOBJReader> reader;
  reader->SetFileName(GLS_BENCHMARK_MODEL);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(reader->GetOutputPort());
  triangles->Update();
  b.mesh = vtkSmartPointer<vtkPolyData>::New();
  b.mesh->DeepCopy(triangles->GetOutput());
  std::printf("bunny mesh: %lld triangles\n", static_cast<long long>(b.mesh->GetNumberOfPolys()));
  b.locator->SetDataSet(b.mesh);
  b.locator->BuildLocator();
  double bounds[6];
  samples->GetBounds(bounds);
  const double diag = std::sqrt(std::pow(bounds[1] - bounds[0], 2) + std::pow(bounds[3] - bounds[2], 2) +
    std::pow(bounds[5] - bounds[4], 2));
  double area = 0;
  for (vtkIdType c = 0; c < b.mesh->GetNumberOfCells(); ++c)
  {
    vtkCell* cell = b.mesh->GetCell(c);
    if (cell->GetNumberOfPoints() == 3)
    {
      double v0[3], v1[3], v2[3];
      cell->GetPoints()->GetPoint(0, v0);
      cell->GetPoints()->GetPoint(1, v1);
      cell->GetPoints()->GetPoint(2, v2);
      area += vtkTriangle::TriangleArea(v0, v1, v2);
    }
  }
  b.spacing = std::sqrt(area / static_cast<double>(count));
  std::mt19937_64 rng(3);
  std::normal_distribution<double> unit(0.0, 1.0);
  const double sigmaA = 0.0025 * diag, sigmaB = 0.0008 * diag, angle = 10.0 * M_PI / 180.0;
  const double width = (bounds[1] - bounds[0]) / 4.0;
  vtkDataArray* nrm = samples->GetPointData()->GetNormals();
  for (vtkIdType i = 0; i < samples->GetNumberOfPoints(); ++i)
  {
    double x[3], n[3];
    samples->GetPoint(i, x);
    nrm->GetTuple(i, n);
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& v : n)
    {
      v /= len;
    }
    const int r = std::min(3, static_cast<int>((x[0] - bounds[0]) / width));
    b.region.push_back(r);
    b.cleanFar.push_back(r == 3 && x[0] > bounds[0] + 3.0 * width + 0.05 * diag ? 1 : 0);
    b.clean.insert(b.clean.end(), { x[0], x[1], x[2] });
    b.cleanNormals.insert(b.cleanNormals.end(), { n[0], n[1], n[2] });
    const double s = unit(rng) * (r == 0 ? sigmaA : (r == 1 ? sigmaB : 0.0));
    b.points.insert(b.points.end(), { x[0] + s * n[0], x[1] + s * n[1], x[2] + s * n[2] });
    double m[3] = { n[0], n[1], n[2] };
    if (r == 0 || r == 2)
    {
      // Rotate the normal by a Gaussian angle about a random tangent axis.
      double axis[3] = { unit(rng), unit(rng), unit(rng) };
      const double along = axis[0] * n[0] + axis[1] * n[1] + axis[2] * n[2];
      for (int a = 0; a < 3; ++a)
      {
        axis[a] -= along * n[a];
      }
      const double al = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
      const double th = unit(rng) * angle;
      for (int a = 0; a < 3; ++a)
      {
        m[a] = std::cos(th) * n[a] + std::sin(th) * axis[a] / al;
      }
    }
    b.normals.insert(b.normals.end(), { m[0], m[1], m[2] });
  }
  return true;
}

/// The acceptance figures for the adaptive result, each with PASS or FAIL.
void printVerdict(const Scores& input, const Scores& adaptive, const Scores& bestGlobal, double spacing)
{
  const auto verdict = [](bool ok) { return ok ? "PASS" : "FAIL"; };
  std::printf("acceptance (adaptive):\n");
  const char* names[2] = { "A", "B" };
  for (int r = 0; r < 2; ++r)
  {
    const double drop = input.rms[r] / adaptive.rms[r];
    std::printf("  %s RMS distance drops %.2fx (>= 3): %s\n", names[r], drop, verdict(drop >= 3.0));
  }
  std::printf("  (information) RMS normal angle: A %.2f -> %.2f deg, C %.2f -> %.2f deg\n", input.angle[0],
    adaptive.angle[0], input.angle[2], adaptive.angle[2]);
  std::printf("  clean part far from the noise: RMS move %.4f spacing (< 0.05): %s; max move %.4f\n",
    adaptive.cleanMoveRms / spacing, verdict(adaptive.cleanMoveRms < 0.05 * spacing), adaptive.cleanMove / spacing);
  std::printf("  RMS distance, all points: adaptive %.4f vs best global %.4f spacing (lower): %s; RMS normal angle "
              "%.2f vs %.2f deg\n",
    adaptive.total / spacing, bestGlobal.total / spacing, verdict(adaptive.total < bestGlobal.total),
    adaptive.totalAngle, bestGlobal.totalAngle);
}

template <typename Score>
void runMethods(vtkPolyData* input, const Score& score, double spacing, double minScale, double maxScale,
  double smoothing, const std::vector<double>& globalScales)
{
  const Scores none = score(input);
  printRow("input (noisy)", 0.0, none, spacing);
  vtkNew<vtkGLSAdaptiveBandwidth> bandwidth;
  bandwidth->SetInputData(input);
  bandwidth->SetScaleUnitsToAbsolute();
  bandwidth->SetMinScale(minScale);
  bandwidth->SetMaxScale(maxScale);
  bandwidth->SetNumberOfScales(40);
  bandwidth->SetScaleSamplingToLogarithmic();
  bandwidth->SetSmoothingRadius(smoothing);
  vtkNew<vtkGLSProjection> adaptive;
  adaptive->SetInputConnection(bandwidth->GetOutputPort());
  const double tBandwidth = seconds([&] { bandwidth->Update(); });
  const double tProject = seconds([&] { adaptive->Update(); });
  const Scores adaptiveScores = score(adaptive->GetOutput());
  printRow("GLS adaptive bandwidth + projection", tBandwidth + tProject, adaptiveScores, spacing);
  double best = 1e300;
  std::string bestName;
  Scores bestScores{};
  double bestTime = 0;
  for (double t : globalScales)
  {
    vtkNew<vtkGLSProjection> global;
    global->SetInputData(input);
    global->SetScaleModeToFixedScale();
    global->SetScaleUnitsToAbsolute();
    global->SetScale(t);
    const double time = seconds([&] { global->Update(); });
    const Scores s = score(global->GetOutput());
    char name[64];
    std::snprintf(name, sizeof name, "GLS projection, global t=%.4g", t);
    printRow(name, time, s, spacing);
    if (s.total < best)
    {
      best = s.total;
      bestName = name;
      bestScores = s;
      bestTime = time;
    }
  }
  printRow("best global: " + bestName.substr(bestName.find("t=")), bestTime, bestScores, spacing);
  printVerdict(none, adaptiveScores, bestScores, spacing);
  for (int iterations : { 20, 100 })
  {
    vtkNew<vtkPointSmoothingFilter> vtkSmoothing;
    vtkSmoothing->SetInputData(input);
    vtkSmoothing->SetNumberOfIterations(iterations);
    const double time = seconds([&] { vtkSmoothing->Update(); });
    printRow("vtkPointSmoothingFilter, " + std::to_string(iterations) + " it.", time,
      score(vtkSmoothing->GetOutput()), spacing);
  }
}

} // namespace

int main(int argc, char** argv)
{
  std::int64_t points = 100000;
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--points"))
    {
      points = std::atoll(argv[++i]);
    }
  }

  const glstest::NoisyCurve curve{ glstest::NoisyCurveSpec() };
  printHeader("Figure 9 curve, 4000 points", curve.spacing());
  runMethods(glstest::makePolyData(curve.Points, curve.Normals), [&](vtkPointSet* out) { return scoreCurve(curve, out); },
    curve.spacing(), 0.004, 0.15, 0.06, { 0.02, 0.04, 0.06, 0.08, 0.09, 0.1, 0.12, 0.15 });

  Bunny bunny;
  if (!makeBunny(bunny, points))
  {
    std::fprintf(stderr, "cannot read %s\n", GLS_BENCHMARK_MODEL);
    return 1;
  }
  auto input = glstest::makePolyData(bunny.points, bunny.normals);
  printHeader(("Bunny, " + std::to_string(points) + " points").c_str(), bunny.spacing);
  const double h = bunny.spacing;
  runMethods(input, [&](vtkPointSet* out) { return bunny.score(out); }, h, 1.0 * h, 5.0 * h, 6.6 * h,
    { 1.67 * h, 3.33 * h, 5.0 * h, 6.67 * h, 10.0 * h });
  std::printf("\nbenchmark complete: the curve and the bunny\n");
  return 0;
}
