/**
 * @class   vtkGLSGeometricVariation
 * @brief   GLS geometric variation nu(p, t) at every point and scale, and each point's pertinent scales.
 *
 * nu(p, t) = WTau dtau^2 + WEta t^2 |deta|^2 + WKappa t^4 dkappa^2 (Mellado et al. 2012, eq. 5): dimensionless and
 * invariant to rigid motion and uniform scaling; low nu means the shape around p is stable at scale t. The
 * derivatives come from the GLSdTau/GLSdEta/GLSdKappa arrays of an upstream vtkGLSScaleSpace when present (see
 * ReuseInputScaleSpace), else they are computed here from points and normals without storing them.
 *
 * Point-data outputs:
 * - GLSGeometricVariation (dimensionless, one component per scale "t=<scale>"): nu; NaN where the fit is undefined.
 * - GLSPertinentScaleCount (integer): number of pertinent scales reported for the point (at most
 *   MaxNumberOfPertinentScales).
 * - GLSPertinentScales (length, MaxNumberOfPertinentScales components, NaN-padded): the scales t_k (0 < k < S-1)
 *   where nu has a strict local minimum over the sampled scales (nu_k < nu_{k-1} - 1e-12, nu_k <= nu_{k+1} + 1e-12; a minimum next
 *   to a NaN does not count); when there are more, the ones with the lowest nu, listed by increasing scale. A point
 *   whose nu is constant (a perfect sphere or plane) has none.
 * Field data: GLSScales (length).
 */
#ifndef vtkGLSGeometricVariation_h
#define vtkGLSGeometricVariation_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSVariationFilterBase.h"

class VTKGLSFILTERS_EXPORT vtkGLSGeometricVariation : public vtkGLSVariationFilterBase
{
public:
  static vtkGLSGeometricVariation* New();
  vtkTypeMacro(vtkGLSGeometricVariation, vtkGLSVariationFilterBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// When on (default) and the input carries the GLSdTau/GLSdEta/GLSdKappa arrays of an upstream vtkGLSScaleSpace
  /// (and its GLSScales), nu is computed from them at their scales instead of refitting; this filter's scale
  /// parameters are then ignored. Off: always refit at this filter's scales.
  vtkSetMacro(ReuseInputScaleSpace, bool);
  vtkGetMacro(ReuseInputScaleSpace, bool);
  vtkBooleanMacro(ReuseInputScaleSpace, bool);
  ///@}

  ///@{
  /// How many pertinent scales to report per point (default 3, at least 1).
  vtkSetMacro(MaxNumberOfPertinentScales, int);
  vtkGetMacro(MaxNumberOfPertinentScales, int);
  ///@}

protected:
  void DescribeSettings(std::vector<SettingRange>& settings) override;

  vtkGLSGeometricVariation();
  ~vtkGLSGeometricVariation() override;

  SampleRequest GetSampleRequest(const vtkGLSRun& run) const override;
  int ComputeOutputs(vtkGLSRun& run) override;

  bool ReuseInputScaleSpace;
  int MaxNumberOfPertinentScales;

private:
  vtkGLSGeometricVariation(const vtkGLSGeometricVariation&) = delete;
  void operator=(const vtkGLSGeometricVariation&) = delete;
};

#endif
