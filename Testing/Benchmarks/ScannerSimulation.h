// A simulated terrestrial scanner: rays from one or more positions on a regular angular grid, denser along the scan
// lines than across them, each keeping its first hit on a triangle mesh. What scanners give and what the normal
// estimation must survive: anisotropic sampling (the Anisotropy option), occlusion, one-sided views. The hit
// triangle's normal, turned to the side the scanner sees, is the ground truth; the scanner position of every point is
// kept (merged scans carry it).
#pragma once

#include "vtkSmartPointer.h"

#include <array>
#include <cstddef>
#include <vector>

class vtkPolyData;

struct ScannerSettings
{
  /// Scanner positions, in the mesh's coordinates. Empty: two positions at 2.5 bounding-box diagonals from the
  /// centre, 20 degrees above it, 110 degrees apart around the vertical (z) axis.
  std::vector<std::array<double, 3>> Positions;
  /// Rays per position along a scan line (a vertical sweep) over the mesh's angular extent.
  int SamplesAlong = 1200;
  /// Samples along a line per line across: the spacing across the lines is Anisotropy times the spacing along.
  double Anisotropy = 10.0;
};

struct ScannerScan
{
  std::vector<double> Points;      ///< 3 per hit
  std::vector<double> Normals;     ///< 3 per hit: the unit normal of the hit triangle, turned towards the ray's
                                   ///< origin (the side a first hit sees: outward on a closed surface)
  std::vector<double> WoundNormals; ///< 3 per hit: the hit triangle's normal as the file winds it (outward on a
                                    ///< consistently wound closed mesh, whichever side the scanner sees)
  std::vector<double> SmoothNormals; ///< 3 per hit: the mesh's vertex normals (area-weighted) interpolated at the
                                     ///< hit, turned like Normals: the smooth surface the facets approximate
  std::vector<double> Viewpoints;  ///< 3 per hit: the position of the scanner that saw it
  std::vector<long long> Cells;    ///< the hit triangle
  std::size_t FlippedTriangles = 0; ///< hits whose triangle the file winds facing away from the scanner
  std::size_t Size() const { return this->Points.size() / 3; }
};

/// Scans the triangle mesh from each position: the rays cover the angular box of the mesh's bounding box seen from
/// there, SamplesAlong rays per line (elevation) and SamplesAlong / Anisotropy lines (azimuth), and keep their first
/// hit. Deterministic.
ScannerScan simulateScanner(vtkPolyData* mesh, const ScannerSettings& settings);

/// The scan as a vtkPolyData of vertices: no normals (what a scanner gives), the true normals as point array
/// "TrueNormals" and the scanner positions as "ScannerPosition" (3 components).
vtkSmartPointer<vtkPolyData> scanAsPolyData(const ScannerScan& scan);

/// Per point: the distance to the nearest crease of the mesh (edges whose dihedral angle exceeds featureAngle
/// degrees), for leaving the points near creases out of a comparison on CAD parts. Infinity without creases.
std::vector<double> distanceToCreases(vtkPolyData* mesh, const ScannerScan& scan, double featureAngle);
