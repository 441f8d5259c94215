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
 * Sigma (SigmaMode): by default it is relative to the data, chosen so that the median f over the points is
 * TargetMedianFeature (features then stand out from a low background, as in the paper's Figure 10), from a sample
 * of at most 20,000 points (every k-th point), never below 1e-3 (so a sphere or a plane keeps f = 0: nu is about
 * 1e-20 there); or an absolute value (SIGMA_ABSOLUTE, Sigma), comparable across datasets.
 *
 * Point-data output: GLSFeature (dimensionless, [0, 1]); NaN where no pair of consecutive scales has a defined nu.
 * Field data: GLSScales (length), GLSSigma (the sigma used, dimensionless).
 *
 * With ScaleSummary on, the same pass also writes what the scales say of each point, one value per point
 * (docs/math.md, "Scale summary"): GLSPertinentScaleCount (the local minima of nu), GLSStableScale (length: the
 * pertinent scale of lowest nu, or where nu has no inner minimum the defined scale of lowest nu), GLSStableTau
 * (length), GLSStableKappa (1/length) and GLSStablePhi (dimensionless) at that scale, GLSMaxVariation (the largest
 * nu, dimensionless) and GLSMaxVariationScale (length). Each is NaN (the count 0) where nu is NaN at every scale.
 * This is what the main job keeps of the scale space by default: memory O(N) whatever the number of scales.
 *
 * With DirectionSummary on as well, the same pass also computes the principal curvatures at every scale and writes each
 * point's steadiest principal direction, the arrays of vtkGLSPrincipalDirections (GLSStableDirectionScale,
 * GLSDirectionTurnRate, GLSAnisotropy, GLSStableShapeIndex, GLSStableDirection, GLSRidgeValley; NaN where no pair of
 * consecutive scales is anisotropic): one fit for both, where the two filters would fit twice.
 *
 * OutputPrecision SINGLE_PRECISION writes these arrays (but the count) as float32: half their memory, for clouds of
 * 10^8 points.
 */
#ifndef vtkGLSContinuousFeatures_h
#define vtkGLSContinuousFeatures_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSVariationFilterBase.h"

class vtkDataArray;

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
  /// Also write the per-point scale summary (see the class documentation; default off). It needs the samples, not
  /// only nu: upstream stored arrays serve when they hold tau, kappa, phi and the derivatives.
  vtkSetMacro(ScaleSummary, bool);
  vtkGetMacro(ScaleSummary, bool);
  vtkBooleanMacro(ScaleSummary, bool);
  ///@}

  ///@{
  /// With ScaleSummary on, also write each point's steadiest principal direction in the same pass (see the class
  /// documentation; default off). On without ScaleSummary is refused with an error. Upstream stored arrays serve when
  /// they hold the principal curvatures too (vtkGLSScaleSpace's StorePrincipalCurvatures); else the filter fits.
  vtkSetMacro(DirectionSummary, bool);
  vtkGetMacro(DirectionSummary, bool);
  vtkBooleanMacro(DirectionSummary, bool);
  ///@}

  ///@{
  /// A scale's principal directions count where k1 - k2 >= AnisotropyThreshold max(|k1|, |k2|) (DirectionSummary;
  /// dimensionless, in [0.01, 1]; default 0.2, as vtkGLSPrincipalDirections').
  vtkSetMacro(AnisotropyThreshold, double);
  vtkGetMacro(AnisotropyThreshold, double);
  ///@}

  enum SigmaModeType
  {
    SIGMA_ABSOLUTE = 0, ///< Sigma as given
    SIGMA_RELATIVE = 1  ///< chosen from the data so that the median feature is TargetMedianFeature
  };

  ///@{
  /// How sigma, the scale of tanh(nu / sigma), is set (default SIGMA_RELATIVE; see the class documentation).
  vtkSetMacro(SigmaMode, int);
  vtkGetMacro(SigmaMode, int);
  void SetSigmaModeToAbsolute() { this->SetSigmaMode(SIGMA_ABSOLUTE); }
  void SetSigmaModeToRelative() { this->SetSigmaMode(SIGMA_RELATIVE); }
  ///@}

  ///@{
  /// The absolute sigma of SIGMA_ABSOLUTE (dimensionless, > 0; otherwise RequestData stops with an error). Default
  /// 0.1.
  vtkSetMacro(Sigma, double);
  vtkGetMacro(Sigma, double);
  ///@}

  ///@{
  /// The median of f that SIGMA_RELATIVE aims at (dimensionless, strictly between 0 and 1; otherwise an error).
  /// Default 0.28: on the bundled meshes with their mesh normals the 95th percentile of f is then 0.57 to 0.93.
  vtkSetMacro(TargetMedianFeature, double);
  vtkGetMacro(TargetMedianFeature, double);
  ///@}

  ///@{
  /// The type of the arrays written (GLSFeature and the scale summary's values; GLSPertinentScaleCount stays int):
  /// vtkAlgorithm::DOUBLE_PRECISION (default: doubles) or vtkAlgorithm::SINGLE_PRECISION (float32, each value rounded
  /// to nearest from the double computed, a relative 6e-8: 32 bytes a point instead of 60 with the summary). Another
  /// value is refused (an error, nothing computed).
  vtkSetMacro(OutputPrecision, int);
  vtkGetMacro(OutputPrecision, int);
  ///@}

  /// The sigma the last run used (NaN before any).
  vtkGetMacro(LastSigma, double);

  ///@{
  /// Measure of the scale integral (default SCALE).
  vtkSetMacro(FeatureMeasure, int);
  vtkGetMacro(FeatureMeasure, int);
  void SetFeatureMeasureToScale() { this->SetFeatureMeasure(SCALE); }
  void SetFeatureMeasureToLogScale() { this->SetFeatureMeasure(LOG_SCALE); }
  ///@}

protected:
  void DescribeSettings(std::vector<SettingRange>& settings) override;

  vtkGLSContinuousFeatures();
  ~vtkGLSContinuousFeatures() override;

  /// Sigma must be positive.
  bool CheckParameters(vtkGLSRun& run) override;
  SampleRequest GetSampleRequest(const vtkGLSRun& run) const override;
  int ComputeOutputs(vtkGLSRun& run) override;

  /// The data-relative sigma of this run (SIGMA_RELATIVE), from a sample of its points. Collective. False if
  /// aborted.
  bool RelativeSigma(vtkGLSRun& run, double& sigma);

  /// GLSFeature, and the scale summary with ScaleSummary on, from the samples in one fused pass. False if aborted.
  bool ComputeFeatureAndSummary(vtkGLSRun& run, double sigma, vtkDataArray* feature);

  bool ReuseInputScaleSpace;
  bool ScaleSummary;
  bool DirectionSummary;
  double AnisotropyThreshold;
  int SigmaMode;
  double Sigma;
  double TargetMedianFeature;
  double LastSigma;
  int FeatureMeasure;
  int OutputPrecision;

private:
  vtkGLSContinuousFeatures(const vtkGLSContinuousFeatures&) = delete;
  void operator=(const vtkGLSContinuousFeatures&) = delete;
};

#endif
