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
}

const Descriptor& Get(Id id)
{
  return Table[id];
}

}
