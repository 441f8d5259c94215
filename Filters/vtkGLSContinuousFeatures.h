/**
 * @class   vtkGLSContinuousFeatures
 * @brief   GLS continuous feature f(p): how much the shape around each point varies across the scales.
 *
 * f(p) = (1/|I|) integral over the sampled scale interval I of tanh(nu(p, t) / Sigma) (Mellado et al. 2012,
 * sec. 5), by the trapezoid rule over the sampled scales, in t (FeatureMeasure = SCALE, default) or in ln t
 * (LOG_SCALE: every octave of scales weighs the same). tanh caps strong variations; f is dimensionless, in [0, 1]:
 * 0 on a sphere or a plane (no variation at any scale), near 1 where the shape changes at every scale.
 *
 * nu comes from an upstream GLSGeometricVariation array when present, else from upstream GLSdTau/GLSdEta/GLSdKappa
 * arrays, else it is computed here from points and normals in a fused pass that stores nothing per scale (memory
 * O(N), not O(N x scales)); see ReuseInputScaleSpace and vtkGLSVariationFilterBase.
 *
 * Point-data output: GLSFeature (dimensionless, [0, 1]); NaN where no pair of consecutive scales has a defined nu.
 * Field data: GLSScales (length).
 */
#ifndef vtkGLSContinuousFeatures_h
#define vtkGLSContinuousFeatures_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSVariationFilterBase.h"

class VTKGLSFILTERS_EXPORT vtkGLSContinuousFeatures : public vtkGLSVariationFilterBase
{
public:
  static vtkGLSContinuousFeatures* New();
  vtkTypeMacro(vtkGLSContinuousFeatures, vtkGLSVariationFilterBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum FeatureMeasureType
  {
    SCALE = 0,    ///< integrate in t
    LOG_SCALE = 1 ///< integrate in ln t
  };

  ///@{
  /// When on (default), nu (or the derivatives it is made of) comes from the arrays of an upstream
  /// vtkGLSGeometricVariation or vtkGLSScaleSpace and their GLSScales, and this filter's scale parameters are
  /// ignored. Off: always refit at this filter's scales.
  vtkSetMacro(ReuseInputScaleSpace, bool);
  vtkGetMacro(ReuseInputScaleSpace, bool);
  vtkBooleanMacro(ReuseInputScaleSpace, bool);
  ///@}

  ///@{
  /// Scale of the tanh remapping of nu (dimensionless, > 0; otherwise RequestData stops with an error).
  /// Default 0.1.
  vtkSetMacro(Sigma, double);
  vtkGetMacro(Sigma, double);
  ///@}

  ///@{
  /// Measure of the scale integral (default SCALE).
  vtkSetClampMacro(FeatureMeasure, int, SCALE, LOG_SCALE);
  vtkGetMacro(FeatureMeasure, int);
  void SetFeatureMeasureToScale() { this->SetFeatureMeasure(SCALE); }
  void SetFeatureMeasureToLogScale() { this->SetFeatureMeasure(LOG_SCALE); }
  ///@}

protected:
  vtkGLSContinuousFeatures();
  ~vtkGLSContinuousFeatures() override;

  /// Sigma must be positive.
  bool CheckParameters(vtkGLSRun& run) override;
  SampleRequest GetSampleRequest(const vtkGLSRun& run) const override;
  int ComputeOutputs(vtkGLSRun& run) override;

  bool ReuseInputScaleSpace;
  double Sigma;
  int FeatureMeasure;

private:
  vtkGLSContinuousFeatures(const vtkGLSContinuousFeatures&) = delete;
  void operator=(const vtkGLSContinuousFeatures&) = delete;
};

#endif
