// Geometry of an ordered curve (the scale-space image's input): its extent, arclengths and in-plane normals.
// Points are interleaved xyz triples in traversal order; a closed curve does not repeat its first point. Lengths are
// in the input's units.
#pragma once

#include <vector>

namespace gls
{

/// Bounding-box diagonal of interleaved points (0 for none).
double boundingDiagonal(const std::vector<double>& points);

/// Cumulative arclength at each curve point, plus (closed curve) the total length after the closing segment.
std::vector<double> curveArclengths(const std::vector<double>& points, bool closed);

/// Unit in-plane normals of a curve in the plane z = 0 (z components 0): perpendicular to p(i+1) - p(i-1)
/// (one-sided at the ends of an open curve), to the left of the traversal (+z up) for an open curve, outward for a
/// closed one (by the sign of its shoelace area). NaN where the tangent vanishes.
std::vector<double> inPlaneCurveNormals(const std::vector<double>& points, bool closed);

} // namespace gls
