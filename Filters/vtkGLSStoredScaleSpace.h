// Reads back the per-scale arrays a vtkGLSScaleSpace wrote (private to the module), so that downstream filters
// reuse them instead of recomputing the fits.
#ifndef vtkGLSStoredScaleSpace_h
#define vtkGLSStoredScaleSpace_h

#include "gls/ScaleSample.h"

#include <cstdint>
#include <vector>

class vtkDataArray;
class vtkPolyData;

class vtkGLSStoredScaleSpace
{
public:
  /// Binds the arrays (descriptors: GLSTau, GLSKappa, GLSFitness; derivatives: GLSdTau, GLSdKappa, GLSdEta) for
  /// the given scales. False if any needed array is missing or has the wrong number of components or tuples.
  bool Bind(vtkPolyData* input, std::size_t scaleCount, bool needDescriptors, bool needDerivatives);

  /// The stored samples of one point; a sample is valid when every bound value is finite. Unbound values are NaN.
  void Read(std::uint64_t pointId, gls::ScaleSample* out) const;

private:
  std::size_t ScaleCount = 0;
  vtkDataArray* Tau = nullptr;
  vtkDataArray* Kappa = nullptr;
  vtkDataArray* Fitness = nullptr;
  vtkDataArray* DTau = nullptr;
  vtkDataArray* DKappa = nullptr;
  vtkDataArray* DEta = nullptr;
};

#endif
