// M4 (docs/performance.md, "Fits in tiles"): a fit cut into spatial tiles by its MemoryBudget against the same fit
// untiled, on a bundled mesh sampled by area.
//
//   glsTiledBenchmark [--models bunny,rocker-arm (bunny)] [--points N (3000000)] [--threads T (2)]
//                     [--tiles K (8)] [--max-scale F (0.08)] [--rounds R (2)]
//
// The fit: the continuous features with their scale summary (as the main job runs them), 20 quadratic scales from
// 0.8% of the diagonal to F (default 8%), Evaluation Auto. The budget: the largest of a descending series (x0.7)
// under which the filter cuts its fit into at least K tiles (read from GetLastTileCount at the fit's first progress
// report, the run then aborted); if the filter refuses first (the ghost bands of the largest scale keep the tiles from
// shrinking), that is reported. Then the untiled and the tiled runs in this process, every point array compared bit
// for bit; then R rounds of each in its own process, alternately, for the wall time (the best of the rounds) and the
// peak resident memory. Target: bit for bit, at most 15% more time.
#include "CommaList.h"
#include "MeshSampler.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkGLSContinuousFeatures.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPolyData.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace
{

struct Options
{
  std::vector<std::string> models = { "bunny" };
  long long points = 3000000;
  int threads = 2;
  int tiles = 8;
  double maxScale = 0.08;
  int rounds = 2;
};

double now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string modelPath(const std::string& model)
{
  return std::string(GLS_BENCHMARK_DATA_DIR) + "/" + (model == "bunny" ? "stanford-bunny" : model) + ".obj";
}

vtkSmartPointer<vtkGLSContinuousFeatures> features(vtkPolyData* cloud, const Options& o, double budget)
{
  auto f = vtkSmartPointer<vtkGLSContinuousFeatures>::New();
  f->SetInputData(cloud);
  f->SetScaleSummary(true);
  f->SetNumberOfScales(20);
  f->SetMaxScale(o.maxScale);
  f->SetNumberOfThreads(o.threads);
  f->SetMemoryBudget(budget);
  return f;
}

/// Silences a filter's error and warning events (the probes' refusals are expected); counts the errors.
struct Quiet
{
  int errors = 0;
  static void onEvent(vtkObject*, unsigned long event, void* self, void*)
  {
    if (event == vtkCommand::ErrorEvent)
    {
      ++static_cast<Quiet*>(self)->errors;
    }
  }
};

/// The tiles the filter cuts its fit into under `budget` (0: refused), the run aborted once the fit has started.
int probeTiles(vtkPolyData* cloud, const Options& o, double budget)
{
  auto f = features(cloud, o, budget);
  Quiet quiet;
  vtkNew<vtkCallbackCommand> silence;
  silence->SetCallback(&Quiet::onEvent);
  silence->SetClientData(&quiet);
  f->AddObserver(vtkCommand::ErrorEvent, silence);
  f->AddObserver(vtkCommand::WarningEvent, silence);
  vtkNew<vtkCallbackCommand> stop;
  stop->SetCallback([](vtkObject* caller, unsigned long, void*, void*) {
    auto* filter = static_cast<vtkGLSContinuousFeatures*>(caller);
    if (filter->GetLastTileCount() > 0)
    {
      filter->AbortExecuteOn();
    }
  });
  f->AddObserver(vtkCommand::ProgressEvent, stop);
  f->Update();
  return quiet.errors > 0 && f->GetLastTileCount() == 0 ? 0 : f->GetLastTileCount();
}

/// Every point array of the output, as doubles, in name order.
std::vector<std::pair<std::string, std::vector<double>>> arraysOf(vtkPointSet* output)
{
  std::vector<std::pair<std::string, std::vector<double>>> arrays;
  vtkPointData* pd = output->GetPointData();
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pd->GetArray(a);
    if (!array || !array->GetName())
    {
      continue;
    }
    std::vector<double> v(static_cast<std::size_t>(array->GetNumberOfValues()));
    for (vtkIdType i = 0; i < array->GetNumberOfValues(); ++i)
    {
      v[static_cast<std::size_t>(i)] = array->GetVariantValue(i).ToDouble();
    }
    arrays.emplace_back(array->GetName(), std::move(v));
  }
  std::sort(arrays.begin(), arrays.end());
  return arrays;
}

/// Arrays that differ in some bit (NaN equal to NaN), by name; "-" for a different set of arrays.
std::vector<std::string> differing(const std::vector<std::pair<std::string, std::vector<double>>>& a,
  const std::vector<std::pair<std::string, std::vector<double>>>& b)
{
  if (a.size() != b.size())
  {
    return { "-" };
  }
  std::vector<std::string> names;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    const auto& x = a[k].second;
    const auto& y = b[k].second;
    bool same = a[k].first == b[k].first && x.size() == y.size();
    for (std::size_t i = 0; same && i < x.size(); ++i)
    {
      same = std::memcmp(&x[i], &y[i], sizeof(double)) == 0 || (std::isnan(x[i]) && std::isnan(y[i]));
    }
    if (!same)
    {
      names.push_back(a[k].first);
    }
  }
  return names;
}

/// Runs the fit in a child process: its wall time and the child's peak resident memory (MiB), or -1 on failure.
std::pair<double, double> timedInChild(vtkPolyData* cloud, const Options& o, double budget)
{
  int pipe[2];
  if (::pipe(pipe) != 0)
  {
    return { -1.0, -1.0 };
  }
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid == 0)
  {
    auto f = features(cloud, o, budget);
    const double t0 = now();
    f->Update();
    const double wall = f->GetOutput()->GetPointData()->GetArray("GLSFeature") ? now() - t0 : -1.0;
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    const double result[2] = { wall, u.ru_maxrss / 1024.0 };
    const ssize_t written = write(pipe[1], result, sizeof(result));
    _exit(written == static_cast<ssize_t>(sizeof(result)) ? 0 : 1);
  }
  close(pipe[1]);
  double result[2] = { -1.0, -1.0 };
  const ssize_t got = read(pipe[0], result, sizeof(result));
  close(pipe[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (got != static_cast<ssize_t>(sizeof(result)))
  {
    return { -1.0, -1.0 };
  }
  return { result[0], result[1] };
}

int runModel(const std::string& model, const Options& o)
{
  auto cloud = sampleMeshSurface(modelPath(model), o.points, 1);
  if (!cloud)
  {
    std::printf("error: cannot sample %s\n", model.c_str());
    return 1;
  }
  // The budget: down from about 400 bytes a point (no tiles) until the fit takes at least o.tiles tiles.
  double budget = 400.0 * static_cast<double>(o.points) / (1024.0 * 1024.0);
  int tiles = probeTiles(cloud, o, budget);
  int fewer = tiles;
  double fewerBudget = budget;
  while (tiles > 0 && tiles < o.tiles && budget > 0.01)
  {
    fewer = tiles;
    fewerBudget = budget;
    budget *= 0.7;
    tiles = probeTiles(cloud, o, budget);
  }
  // Refused below a budget met with fewer tiles: the step may have jumped over the few budgets that take enough
  // tiles (the whole cloud's points and normals stay besides the tiles), so the budgets between are bisected.
  double refused = budget;
  for (int step = 0; tiles == 0 && step < 12; ++step)
  {
    const double middle = 0.5 * (refused + fewerBudget);
    const int cut = probeTiles(cloud, o, middle);
    if (cut >= o.tiles)
    {
      budget = middle;
      tiles = cut;
    }
    else if (cut == 0)
    {
      refused = middle;
    }
    else
    {
      fewer = cut;
      fewerBudget = middle;
    }
  }
  if (tiles < o.tiles)
  {
    std::printf("%-12s the filter refused a budget of %.1f MiB before reaching %d tiles (%d tiles at %.1f MiB; the "
                "ghost bands of the largest scale keep the tiles from shrinking): no M4 at these scales\n",
      model.c_str(), budget, o.tiles, fewer, fewerBudget);
    return 0;
  }
  // Bit for bit, in this process.
  auto whole = features(cloud, o, 0.0);
  whole->Update();
  auto cut = features(cloud, o, budget);
  cut->Update();
  const std::vector<std::string> differ = differing(arraysOf(whole->GetOutput()), arraysOf(cut->GetOutput()));
  std::string differList;
  for (const std::string& name : differ)
  {
    differList += " " + name;
  }
  const int arrayCount = whole->GetOutput()->GetPointData()->GetNumberOfArrays();
  whole = nullptr;
  cut = nullptr;
  // Time and memory, each run in its own process, alternately.
  double wallWhole = 1e300, wallCut = 1e300, peakWhole = 0.0, peakCut = 0.0;
  for (int r = 0; r < o.rounds; ++r)
  {
    const auto a = timedInChild(cloud, o, 0.0);
    const auto b = timedInChild(cloud, o, budget);
    if (a.first < 0.0 || b.first < 0.0)
    {
      std::printf("error: a timed run failed\n");
      return 1;
    }
    wallWhole = std::min(wallWhole, a.first);
    wallCut = std::min(wallCut, b.first);
    peakWhole = std::max(peakWhole, a.second);
    peakCut = std::max(peakCut, b.second);
  }
  const double overhead = wallCut / wallWhole - 1.0;
  std::printf("%-12s %9lld %6.1f MiB %5d %10.1f %10.1f %+8.1f%% %9.0f %9.0f  %s\n", model.c_str(), o.points,
    budget, tiles, wallWhole, wallCut, 100.0 * overhead, peakWhole, peakCut,
    differ.empty() ? (overhead <= 0.15 ? "PASS (bit for bit)" : "FAIL (time)")
                   : ("FAIL: differ:" + differList).c_str());
  std::printf("%-12s (%d point arrays compared)\n", "", arrayCount);
  return differ.empty() ? 0 : 1;
}

} // namespace

int main(int argc, char* argv[])
{
  Options o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    const bool value = i + 1 < argc;
    if (a == "--models" && value)
    {
      o.models = splitCommaList(argv[++i]);
    }
    else if (a == "--points" && value)
    {
      o.points = std::atoll(argv[++i]);
    }
    else if (a == "--threads" && value)
    {
      o.threads = std::atoi(argv[++i]);
    }
    else if (a == "--tiles" && value)
    {
      o.tiles = std::atoi(argv[++i]);
    }
    else if (a == "--max-scale" && value)
    {
      o.maxScale = std::atof(argv[++i]);
    }
    else if (a == "--rounds" && value)
    {
      o.rounds = std::atoi(argv[++i]);
    }
    else
    {
      std::fprintf(stderr,
        "usage: %s [--models a,b] [--points N] [--threads T] [--tiles K] [--max-scale F] [--rounds R]\n", argv[0]);
      return 2;
    }
  }
  std::printf("== M4: continuous features with their summary, 20 scales to %.3g of the diagonal, %d threads; "
              "tiled (at least %d tiles) against untiled (target: bit for bit, at most +15%% time)\n",
    o.maxScale, o.threads, o.tiles);
  std::printf("%-12s %9s %10s %5s %10s %10s %9s %9s %9s  %s\n", "model", "points", "budget", "tiles", "untiled s",
    "tiled s", "overhead", "MiB", "MiB", "verdict");
  int rc = 0;
  for (const std::string& model : o.models)
  {
    rc |= runModel(model, o);
  }
  std::printf("\ntiled benchmark complete\n");
  return rc;
}
