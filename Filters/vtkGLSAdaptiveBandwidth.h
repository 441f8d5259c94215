/**
 * @class   vtkGLSAdaptiveBandwidth
 * @brief   Per-point adaptive bandwidth from the GLS geometric variation (Mellado et al. 2012, sec. 6).
 *
 * The bandwidth of a point is its smallest pertinent scale, found coarse to fine: starting from the largest
 * sampled scale, the scan stops at the first pair of consecutive scales (t_k, t_k+1) where nu rises towards the
 * finer scale faster than Threshold, measured as the dimensionless finite-difference slope
 * -(nu(t_k+1) - nu(t_k)) / ln(t_k+1 / t_k) (= -t dnu/dt), or where nu(t_k) is undefined (too few neighbours); the
 * raw bandwidth is then t_k+1. Noise makes nu rise sharply at fine scales; a feature at distance d makes it rise as
 * t comes down to d, which keeps the bandwidth below the feature. Without such a pair the raw bandwidth is the
 * smallest scale. The raw values are then regularized by a spatial smoothing: a weighted mean over the points
 * within SmoothingRadius (weight (1 - d^2/r^2)^2).
 *
 * Scales: the shared scale parameters of vtkGLSScaleFilterBase (sample the noise's range: the smallest scale a few
 * sample spacings, the largest about the size of the smallest feature to keep). nu comes from an upstream
 * GLSGeometricVariation array when present (ReuseInputScaleSpace), else from a fused pass that stores nothing per
 * scale.
 *
 * Point-data output: GLSBandwidth (length, the smoothed bandwidth, active scalars) and GLSRawBandwidth (length,
 * before smoothing). NaN for points with non-finite coordinates, where nu is undefined at the largest scale, and
 * (smoothed) where no point within SmoothingRadius has a raw value. Field data: GLSScales, GLSBackend. Feed the
 * result to vtkGLSProjection to denoise with a per-point support.
 */
#ifndef vtkGLSAdaptiveBandwidth_h
#define vtkGLSAdaptiveBandwidth_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSVariationFilterBase.h"

class VTKGLSFILTERS_EXPORT vtkGLSAdaptiveBandwidth : public vtkGLSVariationFilterBase
{
public:
  static vtkGLSAdaptiveBandwidth* New();
  vtkTypeMacro(vtkGLSAdaptiveBandwidth, vtkGLSVariationFilterBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// When on (default), nu comes from the arrays of an upstream vtkGLSGeometricVariation or vtkGLSScaleSpace and
  /// their GLSScales, and this filter's scale parameters are ignored. Off: always refit at this filter's scales.
  vtkSetMacro(ReuseInputScaleSpace, bool);
  vtkGetMacro(ReuseInputScaleSpace, bool);
  vtkBooleanMacro(ReuseInputScaleSpace, bool);
  ///@}

  ///@{
  /// Threshold on the slope -t dnu/dt (dimensionless, >= 0). Default 0.01, the paper's value. Lower values stop
  /// the scan sooner (larger bandwidths).
  vtkSetMacro(Threshold, double);
  vtkGetMacro(Threshold, double);
  ///@}

  ///@{
  /// Radius of the spatial smoothing of the raw bandwidths, in ScaleUnits (fraction of the bounding-box diagonal by
  /// default). 0 turns the smoothing off. Default 0.01.
  vtkSetMacro(SmoothingRadius, double);
  vtkGetMacro(SmoothingRadius, double);
  ///@}

protected:
  void DescribeSettings(std::vector<SettingRange>& settings) override;

  vtkGLSAdaptiveBandwidth();
  ~vtkGLSAdaptiveBandwidth() override;

  SampleRequest GetSampleRequest(const vtkGLSRun& run) const override;
  /// Distributed runs: the fit uses the ghosts within the largest scale, the smoothing the ghosts' raw bandwidths
  /// within SmoothingRadius (a second exchange, of the raw values).
  int ComputeOutputs(vtkGLSRun& run) override;

  bool ReuseInputScaleSpace;
  double Threshold;
  double SmoothingRadius;

private:
  vtkGLSAdaptiveBandwidth(const vtkGLSAdaptiveBandwidth&) = delete;
  void operator=(const vtkGLSAdaptiveBandwidth&) = delete;
};

#endif
