// Open3D 0.16 (Debian package python3-open3d) as a benchmark peer: PointCloud.estimate_normals with a hybrid
// k-nearest / radius search (KDTreeSearchParamHybrid), run by /usr/bin/python3 in a process of its own
// (open3d_normals.py; it pulls Debian's VTK 9.1, which must never meet ParaView's). Points go there and normals come
// back as raw doubles; the estimate_normals call is timed inside the process, apart from start-up and I/O.
#pragma once

#include <string>
#include <vector>

struct Open3DResult
{
  bool ok = false;
  std::string message;        ///< why not ok (Python or open3d missing, failed run with its output)
  std::string version;
  double computeSeconds = 0.0; ///< the estimate_normals call alone
  double computeCpuSeconds = 0.0;
  int computeThreads = 0;      ///< threads that worked during the call (each >= 10% of a core)
  double processSeconds = 0.0; ///< the whole process: interpreter and open3d start-up, I/O, compute
  std::vector<double> normals; ///< 3n, unit, unoriented
};

/// Normals of the n interleaved points from their maxNeighbors nearest within `radius`, on `threads` OpenMP
/// threads (0: Open3D's default, all cores).
Open3DResult open3dNormals(const std::vector<double>& xyz, double radius, int maxNeighbors, int threads);
