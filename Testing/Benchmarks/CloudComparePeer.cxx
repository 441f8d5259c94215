#include "CloudComparePeer.h"

#include "PeerProcess.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace
{

bool writeXyz(const std::string& path, const std::vector<double>& xyz)
{
  FILE* f = std::fopen(path.c_str(), "w");
  if (!f)
  {
    return false;
  }
  for (std::size_t i = 0; i < xyz.size(); i += 3)
  {
    std::fprintf(f, "%.9g %.9g %.9g\n", xyz[i], xyz[i + 1], xyz[i + 2]);
  }
  return std::fclose(f) == 0;
}

/// The columns after x y z of every row of an ASC file (space-separated; "nan" allowed), `count` per row.
bool readColumns(const std::string& path, std::size_t rows, int count, std::vector<double>& columns)
{
  FILE* f = std::fopen(path.c_str(), "r");
  if (!f)
  {
    return false;
  }
  columns.assign(rows * count, 0.0);
  char* line = nullptr;
  std::size_t capacity = 0;
  std::size_t row = 0;
  bool ok = true;
  while (ok && getline(&line, &capacity, f) >= 0)
  {
    if (row >= rows)
    {
      ok = false;
      break;
    }
    char* p = line;
    for (int c = 0; c < 3 + count; ++c)
    {
      char* end = nullptr;
      const double v = std::strtod(p, &end);
      if (end == p)
      {
        ok = false;
        break;
      }
      if (c >= 3)
      {
        columns[row * count + (c - 3)] = v;
      }
      p = end;
    }
    ++row;
  }
  std::free(line);
  std::fclose(f);
  return ok && row == rows;
}

CloudCompareResult runCloudCompare(const std::vector<double>& xyz, const std::vector<std::string>& commands,
  int columnCount, int threads)
{
  CloudCompareResult r;
  if (findOnPath("CloudCompare").empty())
  {
    r.message = "no CloudCompare on PATH (Debian package cloudcompare, installed by .ci/install-deps)";
    return r;
  }
  ScratchDirectory dir;
  if (dir.path().empty())
  {
    r.message = "cannot create a scratch directory";
    return r;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const std::string cloud = dir.file("cloud.xyz"), result = dir.file("result.asc");
  if (!writeXyz(cloud, xyz))
  {
    r.message = "cannot write " + cloud;
    return r;
  }
  r.writeInputSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::vector<std::string> argv = { "CloudCompare", "-SILENT", "-NO_TIMESTAMP", "-AUTO_SAVE", "OFF", "-O",
    cloud };
  argv.insert(argv.end(), commands.begin(), commands.end());
  for (const char* a : { "-C_EXPORT_FMT", "ASC", "-SAVE_CLOUDS", "FILE" })
  {
    argv.emplace_back(a);
  }
  argv.push_back(result);
  const PeerRun run = runPeer(onCoresLineBuffered(threads, argv), { "QT_QPA_PLATFORM=offscreen" });
  const int loaded = run.find("loaded successfully");
  const int saving = run.find("[SAVING]", loaded);
  const int saved = run.find("saved successfully", saving);
  if (!run.ok() || loaded < 0 || saving < 0 || saved < 0)
  {
    r.message = "CloudCompare failed (exit status " + std::to_string(run.exitStatus) + ")" +
      (run.error.empty() ? "" : ": " + run.error) + "; its last lines:\n" + run.tail();
    return r;
  }
  r.importSeconds = run.lines[loaded].seconds;
  r.computeSeconds = run.lines[saving].seconds - run.lines[loaded].seconds;
  r.computeCpuSeconds = run.lines[saving].cpuSeconds - run.lines[loaded].cpuSeconds;
  r.computeThreads = run.busyThreads(loaded, saving);
  r.exportSeconds = run.lines[saved].seconds - run.lines[saving].seconds;
  r.columnCount = columnCount;
  if (!readColumns(result, xyz.size() / 3, columnCount, r.columns))
  {
    r.message = "CloudCompare's " + result + " does not hold " + std::to_string(xyz.size() / 3) +
      " rows of " + std::to_string(3 + columnCount) + " numbers";
    return r;
  }
  r.ok = true;
  return r;
}

std::string lengthArgument(double r)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", r);
  return text;
}

} // namespace

CloudCompareResult cloudCompareMeanCurvature(const std::vector<double>& xyz, const std::vector<double>& radii,
  int threads, double unitScale)
{
  std::vector<std::string> commands;
  for (double r : radii)
  {
    commands.insert(commands.end(), { "-CURV", "MEAN", lengthArgument(r * unitScale) });
  }
  std::vector<double> scaled(xyz);
  for (double& x : scaled)
  {
    x *= unitScale;
  }
  CloudCompareResult r = runCloudCompare(scaled, commands, static_cast<int>(radii.size()), threads);
  for (double& h : r.columns)
  {
    h *= unitScale;
  }
  return r;
}

CloudCompareResult cloudCompareOctreeNormals(const std::vector<double>& xyz, double radius, int threads)
{
  return runCloudCompare(xyz, { "-OCTREE_NORMALS", lengthArgument(radius), "-MODEL", "LS" }, 3, threads);
}
