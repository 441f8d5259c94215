// Geometry of an ordered curve for vtkGLSScaleSpaceImage (private helper): extracting the ordered points of a
// polyline, fitting its plane, in-plane normals and arclengths. Lengths are in the input's units.
#ifndef vtkGLSCurve_h
#define vtkGLSCurve_h

#include "vtkType.h"

#include <string>
#include <vector>

class vtkPolyData;

namespace vtkGLSCurve
{

/// The ordered points of a curve; a closed curve does not repeat its first point.
struct Curve
{
  std::vector<double> Points; ///< 3 per point, in traversal order
  std::vector<vtkIdType> Ids; ///< the input point id of each curve point
  bool Closed = false;
};

/// The points of the first line cell (or all points in order when there is none). closedMode follows
/// vtkGLSScaleSpaceImage::ClosedType (0 auto, 1 open, 2 closed). Returns an error message, or "" on success.
std::string Extract(vtkPolyData* input, int closedMode, Curve& curve);

/// Bounding-box diagonal of interleaved points.
double Diagonal(const std::vector<double>& points);

/// Best-fit (least-squares) plane of the points: an orthonormal right-handed frame (E1, E2, Normal) at the
/// centroid. Normal is the plane normal whose largest-magnitude component is positive.
struct Plane
{
  double Center[3];
  double E1[3];
  double E2[3];
  double Normal[3];
  double MaxDistance = 0.0; ///< largest distance of a point to the plane
};
Plane FitPlane(const std::vector<double>& points);

/// Coordinates of a point (isPoint) or of a vector in the frame (E1, E2, Normal) of the plane.
void ToPlane(const Plane& plane, const double* in, double* out, bool isPoint);

/// Unit in-plane normals of a curve in the plane z = 0 (z components 0): perpendicular to p(i+1) - p(i-1)
/// (one-sided at the ends of an open curve), to the left of the traversal (+z up) for an open curve, outward for a
/// closed one. NaN where the tangent vanishes.
std::vector<double> InPlaneNormals(const std::vector<double>& points, bool closed);

/// Cumulative arclength at each curve point, plus (closed curve) the total length after the closing segment.
std::vector<double> Arclengths(const std::vector<double>& points, bool closed);

}

#endif
