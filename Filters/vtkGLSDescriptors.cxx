#include "vtkGLSDescriptors.h"

#include <type_traits>

namespace vtkGLSDescriptors
{
namespace
{
using gls::ScaleSample;
static_assert(std::is_standard_layout<ScaleSample>::value, "descriptor values are read at their offsets");
static_assert(sizeof(gls::Vec3) == 3 * sizeof(double), "a 3-vector descriptor is three consecutive doubles");

const Descriptor Table[NUMBER_OF_DESCRIPTORS] = {
  { "GLSTau", 1, offsetof(ScaleSample, tau), false, STORE_TAU, DESCRIPTOR, "length",
    "signed offset from the point to the fitted surface, positive on the side the normals point to" },
  { "GLSEta", 3, offsetof(ScaleSample, eta), false, STORE_ETA, WRITTEN_ONLY, "unit vector",
    "normal of the fitted field at the point" },
  { "GLSKappa", 1, offsetof(ScaleSample, kappa), false, STORE_KAPPA, DESCRIPTOR, "1/length",
    "signed curvature 1/radius, positive for a sphere with outward normals, 0 for a plane" },
  { "GLSFitness", 1, offsetof(ScaleSample, phi), false, STORE_FITNESS, DESCRIPTOR, "dimensionless, [0, 1]",
    "the paper's fitness phi (1: the normals agree with the sphere; Ponca's fitness() is 1 - phi)" },
  { "GLSdTau", 1, offsetof(ScaleSample, dtau), false, STORE_DERIVATIVES, DERIVATIVE, "dimensionless",
    "d tau / d t" },
  { "GLSdEta", 3, offsetof(ScaleSample, deta), false, STORE_DERIVATIVES, DERIVATIVE, "1/length",
    "d eta / d t" },
  { "GLSdKappa", 1, offsetof(ScaleSample, dkappa), false, STORE_DERIVATIVES, DERIVATIVE, "1/length^2",
    "d kappa / d t" },
  { "GLSNeighborCount", 1, offsetof(ScaleSample, neighbors), true, STORE_NEIGHBOR_COUNT, WRITTEN_ONLY, "count",
    "neighbours strictly inside the ball of radius t" },
};

double Component(const gls::Vec3& v, int component)
{
  return component == 0 ? v.x : (component == 1 ? v.y : v.z);
}

void SetComponent(gls::Vec3& v, int component, double value)
{
  (component == 0 ? v.x : (component == 1 ? v.y : v.z)) = value;
}

const CurvatureArray CurvatureTable[NUMBER_OF_CURVATURE_ARRAYS] = {
  { "GLSK1", 1, [](const gls::PrincipalCurvatures& c, double, int) { return c.k1; },
    [](gls::PrincipalCurvatures& c, int, double v) { c.k1 = v; }, "1/length",
    "the larger principal curvature, positive on a sphere with outward normals" },
  { "GLSK2", 1, [](const gls::PrincipalCurvatures& c, double, int) { return c.k2; },
    [](gls::PrincipalCurvatures& c, int, double v) { c.k2 = v; }, "1/length", "the smaller principal curvature" },
  { "GLSPrincipalDirection1", 3, [](const gls::PrincipalCurvatures& c, double, int j) { return Component(c.d1, j); },
    [](gls::PrincipalCurvatures& c, int j, double v) { SetComponent(c.d1, j, v); }, "unit vector",
    "direction of k1, tangent (its largest component positive); NaN at an umbilic" },
  { "GLSPrincipalDirection2", 3, [](const gls::PrincipalCurvatures& c, double, int j) { return Component(c.d2, j); },
    [](gls::PrincipalCurvatures& c, int j, double v) { SetComponent(c.d2, j, v); }, "unit vector",
    "direction of k2, eta x d1; NaN at an umbilic" },
  { "GLSMeanCurvature", 1, [](const gls::PrincipalCurvatures& c, double, int) { return gls::meanCurvature(c); },
    nullptr, "1/length", "(k1 + k2) / 2, kappa on a sphere" },
  { "GLSGaussianCurvature", 1,
    [](const gls::PrincipalCurvatures& c, double, int) { return gls::gaussianCurvature(c); }, nullptr, "1/length^2",
    "k1 k2" },
  { "GLSShapeIndex", 1, [](const gls::PrincipalCurvatures& c, double t, int) { return gls::shapeIndex(c, t); },
    nullptr, "dimensionless, [-1, 1]",
    "Koenderink's (2/pi) atan((k1 + k2) / (k1 - k2)): 1 dome, 1/2 ridge, 0 saddle, -1/2 valley, -1 cup; NaN where "
    "flat at the scale" },
  { "GLSCurvedness", 1, [](const gls::PrincipalCurvatures& c, double, int) { return gls::curvedness(c); },
    nullptr, "1/length", "sqrt((k1^2 + k2^2) / 2)" },
};
}

const Descriptor& Get(Id id)
{
  return Table[id];
}

const CurvatureArray& GetCurvature(CurvatureId id)
{
  return CurvatureTable[id];
}

}
