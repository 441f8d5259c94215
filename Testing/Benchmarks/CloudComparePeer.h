// CloudCompare 2.11 (Debian package cloudcompare) as a benchmark peer, run headless from its command line
// (QT_QPA_PLATFORM=offscreen) on a cloud written as an ASCII .xyz file:
//   CloudCompare -SILENT -NO_TIMESTAMP -AUTO_SAVE OFF -O cloud.xyz <commands> -C_EXPORT_FMT ASC -SAVE_CLOUDS FILE out
// Its import, compute and export are timed apart from the time stamps of its log lines ("loaded successfully",
// "[SAVING]", "saved successfully").
//
// What it computes (CCCoreLib Neighbourhood::computeCurvature, checked here on a sphere of radius 2: 0.500):
// -CURV MEAN r fits z = a + bx + cy + dx^2 + exy + fy^2 by least squares to the neighbours within r (unweighted),
// over the coordinate plane closest to their best-fitting plane, and returns |H| = |k1 + k2| / 2 of that height
// field at the point: unsigned, 1/R on a sphere of radius R. -OCTREE_NORMALS r -MODEL LS: the normal of the
// least-squares plane of the neighbours within r (PCA), points and normals in float.
#pragma once

#include <string>
#include <vector>

struct CloudCompareResult
{
  bool ok = false;
  std::string message;          ///< why not ok (peer missing, failed run with its log)
  double importSeconds = 0.0;   ///< start-up and reading the .xyz file
  double computeSeconds = 0.0;  ///< the commands
  double computeCpuSeconds = 0.0;
  int computeThreads = 0;       ///< threads that worked during the compute (each >= 10% of a core)
  double exportSeconds = 0.0;   ///< writing the ASCII result
  double writeInputSeconds = 0.0; ///< this process writing the .xyz file (not CloudCompare's)
  std::vector<double> columns;  ///< per point, the exported columns after x y z (row-major), float precision
  int columnCount = 0;
};

/// Mean curvature |H| (1/length) of every point at each radius: columns[i * radii.size() + k]. CloudCompare gets
/// the cloud and the radii multiplied by `unitScale` and its |H| is multiplied back: its quadric fit is not
/// invariant to the unit (measured, 20,000 points on a sphere of radius 0.05, kernel 0.005: median |H| 4.7e-9
/// instead of 20; the same sphere in units 1,000 times smaller, radius 50 and kernel 5: 0.01999 for 0.02), so a
/// cloud 0.25 long like the bunny needs it.
CloudCompareResult cloudCompareMeanCurvature(const std::vector<double>& xyz, const std::vector<double>& radii,
  int threads, double unitScale);

/// Unit normals (up to sign) of every point from the plane through its neighbours within `radius`: columns 3n.
CloudCompareResult cloudCompareOctreeNormals(const std::vector<double>& xyz, double radius, int threads);
