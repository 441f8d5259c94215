// The ordered curve of a vtkPolyData for vtkGLSScaleSpaceImage (private helper): the points of its first polyline,
// open or closed. Its geometry (plane, arclengths, in-plane normals) is the core's: gls/CurveGeometry.h and
// gls/Planarity.h.
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

}

#endif
