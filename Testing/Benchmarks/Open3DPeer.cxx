#include "Open3DPeer.h"

#include "PeerProcess.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <unistd.h>

namespace
{

bool writeDoubles(const std::string& path, const std::vector<double>& v)
{
  FILE* f = std::fopen(path.c_str(), "wb");
  const bool ok = f && std::fwrite(v.data(), sizeof(double), v.size(), f) == v.size();
  return f && std::fclose(f) == 0 && ok;
}

bool readDoubles(const std::string& path, std::vector<double>& v)
{
  FILE* f = std::fopen(path.c_str(), "rb");
  const bool ok = f && std::fread(v.data(), sizeof(double), v.size(), f) == v.size();
  return f && std::fclose(f) == 0 && ok;
}

} // namespace

Open3DResult open3dNormals(const std::vector<double>& xyz, double radius, int maxNeighbors, int threads)
{
  Open3DResult r;
  if (access(GLS_BENCHMARK_PYTHON3, X_OK) != 0)
  {
    r.message = std::string("no ") + GLS_BENCHMARK_PYTHON3 + " (Debian's python3, with python3-open3d)";
    return r;
  }
  ScratchDirectory dir;
  if (dir.path().empty())
  {
    r.message = "cannot create a scratch directory";
    return r;
  }
  const std::string points = dir.file("points.f64"), normals = dir.file("normals.f64");
  std::vector<std::string> environment;
  if (threads > 0)
  {
    environment.push_back("OMP_NUM_THREADS=" + std::to_string(threads));
  }
  char radiusText[32];
  std::snprintf(radiusText, sizeof radiusText, "%.17g", radius);
  PeerRun run;
  if (writeDoubles(points, xyz))
  {
    run = runPeer({ GLS_BENCHMARK_PYTHON3, GLS_BENCHMARK_OPEN3D_SCRIPT, points, normals, radiusText,
                    std::to_string(maxNeighbors) },
      environment);
  }
  const int report = run.find("open3d ");
  r.normals.resize(xyz.size());
  if (run.ok() && report >= 0 && readDoubles(normals, r.normals))
  {
    std::istringstream fields(run.lines[report].text);
    std::string word;
    fields >> word >> r.version >> word >> r.computeSeconds >> r.computeCpuSeconds >> word >> r.computeThreads;
    r.processSeconds = run.seconds;
    r.ok = true;
  }
  else if (run.exitStatus == 3)
  {
    r.message = run.lines.empty() ? "open3d missing" : run.lines.back().text;
  }
  else
  {
    r.message = "the Open3D run failed (exit status " + std::to_string(run.exitStatus) + ")" +
      (run.error.empty() ? "" : ": " + run.error) + "; its last lines:\n" + run.tail();
  }
  return r;
}
