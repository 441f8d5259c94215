// Whether an input is planar, decided in one place. The project's "2D input" is a cloud whose points all lie in one
// plane z = const: normal estimation then gives in-plane normals to curve-like neighbourhoods, and a 2D curve (normals
// in that plane too) is fitted with the 2D minimum of 3 neighbours (the 3D fit reduces exactly to the circle fit).
// A curve in any other plane is recognised by its least-squares plane (fitPlane), then rotated into z = 0.
#pragma once

#include <cstddef>

namespace gls
{

/// Where points lie with respect to the planes z = const.
struct PlaneZ
{
  bool any = false;    ///< some point counts
  bool planar = false; ///< every point that counts lies in the plane z = `z` (false when none counts)
  double z = 0.0;
};

/// The points with finite coordinates: do they lie in one plane z = const? (Normal estimation's 2D input.)
PlaneZ commonZ(const double* xyz, std::size_t n);

/// The points that take part in the fits (finite coordinates and a finite non-zero normal): do they lie in one
/// plane z = const with normals whose z component is 0? (The fits' 2D input: a curve in the xy-plane.) Points left
/// out of the fits do not count, so they cannot switch a 2D curve to 3D.
PlaneZ twoDimensionalFitInput(const double* xyz, const double* normals, std::size_t n);

/// Least-squares plane of points: an orthonormal right-handed frame (e1, e2, normal) at the centroid, e1 the
/// direction of largest spread, `normal` the one of least spread with its largest-magnitude component positive.
struct PlaneFit
{
  double center[3];
  double e1[3];
  double e2[3];
  double normal[3];
  double maxDistance = 0.0; ///< largest distance of a point to the plane (length)
};

/// The plane of n interleaved points (n >= 1; all finite).
PlaneFit fitPlane(const double* xyz, std::size_t n);

/// Coordinates of a point (isPoint: relative to the centre) or of a vector in the frame (e1, e2, normal).
void toPlaneFrame(const PlaneFit& plane, const double* in, double* out, bool isPoint);

} // namespace gls
