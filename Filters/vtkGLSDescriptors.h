// The per-scale descriptors of a GLS fit as point-data arrays (private to the module): one table from which
// vtkGLSScaleSpace writes its arrays, the memory estimate counts their bytes, the consumers read them back
// (vtkGLSSampleSource) and every filter finds them by name. Adding a descriptor: compute it in the core (a field of
// gls::ScaleSample and its fit), add its row here, and give it a Store switch (vtkGLSScaleSpace and its XML
// checkbox) unless it joins one that exists. See docs/architecture.md.
#ifndef vtkGLSDescriptors_h
#define vtkGLSDescriptors_h

#include "gls/ScaleSample.h"
#include "gls/ShapeOperator.h"

#include <cstddef>

namespace vtkGLSDescriptors
{

/// The rows of the table, in the order vtkGLSScaleSpace adds its arrays.
enum Id
{
  TAU = 0,
  ETA,
  KAPPA,
  FITNESS,
  DTAU,
  DETA,
  DKAPPA,
  NEIGHBOR_COUNT,
  NUMBER_OF_DESCRIPTORS
};

/// The vtkGLSScaleSpace switch (StoreTau, ...) that writes a descriptor.
enum Switch
{
  STORE_TAU = 0,
  STORE_ETA,
  STORE_KAPPA,
  STORE_FITNESS,
  STORE_DERIVATIVES,
  STORE_NEIGHBOR_COUNT,
  NUMBER_OF_SWITCHES
};

/// What a consumer reads back from stored arrays: the descriptors of the dissimilarity (tau, kappa, phi), or the
/// derivatives of the geometric variation. WRITTEN_ONLY arrays (eta, the neighbour count) are never read back.
enum Use
{
  WRITTEN_ONLY = 0,
  DESCRIPTOR = 1,
  DERIVATIVE = 2
};

struct Descriptor
{
  const char* Name;      ///< point-data array name
  int Components;        ///< values per scale; 3-vectors are stored scale-major: x, y, z of t_0, then of t_1, ...
  std::size_t Offset;    ///< where its consecutive double values sit in a gls::ScaleSample
  bool Integer;          ///< stored as a vtkIntArray whatever the output precision
  Switch StoredBy;       ///< the Store switch that writes it
  Use ReadBack;          ///< what a consumer reads it back for
  const char* Units;     ///< unit of the values
  const char* Meaning;   ///< one line for the documentation
};

/// The row of one descriptor.
const Descriptor& Get(Id id);

/// Value `component` of descriptor d in sample s.
inline double Value(const Descriptor& d, const gls::ScaleSample& s, int component)
{
  return reinterpret_cast<const double*>(reinterpret_cast<const char*>(&s) + d.Offset)[component];
}

/// The principal-curvature arrays (vtkGLSScaleSpace's StorePrincipalCurvatures), in the order it adds them: each
/// from the gls::PrincipalCurvatures of a point at one scale (ShapeOperator.h), in the layout of the descriptors.
enum CurvatureId
{
  K1 = 0,
  K2,
  PRINCIPAL_DIRECTION1,
  PRINCIPAL_DIRECTION2,
  MEAN_CURVATURE,
  GAUSSIAN_CURVATURE,
  SHAPE_INDEX,
  CURVEDNESS,
  NUMBER_OF_CURVATURE_ARRAYS
};

struct CurvatureArray
{
  const char* Name;    ///< point-data array name
  int Components;      ///< values per scale (3-vectors scale-major, as the descriptors)
  /// Value `component` at scale t.
  double (*Value)(const gls::PrincipalCurvatures& c, double t, int component);
  /// Sets value `component` of c from a stored array (consumers read the four base arrays back); null for the
  /// arrays derived from them.
  void (*Read)(gls::PrincipalCurvatures& c, int component, double value);
  const char* Units;   ///< unit of the values
  const char* Meaning; ///< one line for the documentation
};

/// The row of one principal-curvature array.
const CurvatureArray& GetCurvature(CurvatureId id);

/// Sets value `component` of descriptor d in sample s.
inline void SetValue(const Descriptor& d, gls::ScaleSample& s, int component, double value)
{
  reinterpret_cast<double*>(reinterpret_cast<char*>(&s) + d.Offset)[component] = value;
}

}

#endif
