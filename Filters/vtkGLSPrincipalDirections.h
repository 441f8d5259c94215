/**
 * @class   vtkGLSPrincipalDirections
 * @brief   Where each point's principal directions are most stable over the scales, and the surface there: fused.
 *
 * The principal curvatures and directions of the GLS fit at every scale (the derivative of the fitted normal field
 * over positions; vtkGLSScaleSpace's StorePrincipalCurvatures, docs/math.md) are reduced point by point as they are
 * computed, so that nothing is stored per scale (like vtkGLSContinuousFeatures, for clouds of 10^7 points). Among the
 * pairs of consecutive scales where both are anisotropic (k1 - k2 >= AnisotropyThreshold max(|k1|, |k2|)) with defined
 * directions, the steadiest is the one whose direction d1 turns least per unit of log t (gls::steadiestDirection).
 *
 * Point-data outputs (NaN where no pair of consecutive scales is anisotropic: spheres, planes, umbilics):
 * - GLSStableDirectionScale (length): sqrt(t_k t_(k+1)) of the steadiest pair.
 * - GLSDirectionTurnRate (radians per unit of log t): how much d1 turns there.
 * - GLSAnisotropy (dimensionless, [0, 1]): (k1 - k2) / (|k1| + |k2|) there (1: one curvature is 0, a cylinder).
 * - GLSStableShapeIndex (dimensionless, [-1, 1]): Koenderink's shape index there (1/2 ridge, -1/2 valley).
 * - GLSStableDirection (3 components, unit, the active vectors: glyphs show it): d1 there, its largest component
 *   positive.
 * - GLSRidgeValley (the active scalars): +1 on a ridge (stable shape index in [3/8, 5/8]), -1 in a valley
 *   ([-5/8, -3/8]), 0 elsewhere.
 * With DirectionScale set (> 0), the principal curvatures at that one scale too, for glyphs (the active vectors are
 * then GLSPrincipalDirection1AtScale): GLSPrincipalDirection1AtScale and GLSPrincipalDirection2AtScale (3 components,
 * unit, tangent; NaN where the fit is undefined or umbilic), GLSK1AtScale and GLSK2AtScale (1/length; NaN where the
 * fit is undefined), and the field value GLSDirectionScale (length), the analysed scale they are at.
 * Any Evaluation (Auto: exact for small balls, the multi-resolution one for large ones), on the CPU. Field data:
 * GLSScales (length).
 */
#ifndef vtkGLSPrincipalDirections_h
#define vtkGLSPrincipalDirections_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSScaleFilterBase.h"

class VTKGLSFILTERS_EXPORT vtkGLSPrincipalDirections : public vtkGLSScaleFilterBase
{
public:
  static vtkGLSPrincipalDirections* New();
  vtkTypeMacro(vtkGLSPrincipalDirections, vtkGLSScaleFilterBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// When on (default) and the input carries the GLSK1, GLSK2, GLSPrincipalDirection1 and 2 arrays of an upstream
  /// vtkGLSScaleSpace (StorePrincipalCurvatures) with its GLSScales, they are reduced at their scales instead of
  /// refitting (this filter's scale parameters are then ignored). Off: always refit at this filter's scales.
  vtkSetMacro(ReuseInputScaleSpace, bool);
  vtkGetMacro(ReuseInputScaleSpace, bool);
  vtkBooleanMacro(ReuseInputScaleSpace, bool);
  ///@}

  ///@{
  /// A scale's directions count where k1 - k2 >= AnisotropyThreshold max(|k1|, |k2|) (dimensionless, in
  /// [0.01, 1]; default 0.2: below it the directions turn with the sampling's noise).
  vtkSetMacro(AnisotropyThreshold, double);
  vtkGetMacro(AnisotropyThreshold, double);
  ///@}

  ///@{
  /// A scale (in ScaleUnits, like MinScale; default 0: none) whose principal curvatures and directions are written
  /// too, for glyphs: those of the analysed scale nearest to it in log t (with ReuseInputScaleSpace, of the upstream
  /// scales). A value outside the analysed scales' range is refused with an error (the message gives the range).
  vtkSetMacro(DirectionScale, double);
  vtkGetMacro(DirectionScale, double);
  ///@}

  ///@{
  /// The type of the arrays written: vtkAlgorithm::DOUBLE_PRECISION (default: doubles) or SINGLE_PRECISION (float32,
  /// each value rounded to nearest from the double computed, a relative 6e-8: half their memory, for clouds of 10^8
  /// points). Another value is refused (an error, nothing computed).
  vtkSetMacro(OutputPrecision, int);
  vtkGetMacro(OutputPrecision, int);
  ///@}

protected:
  void DescribeSettings(std::vector<SettingRange>& settings) override;

  vtkGLSPrincipalDirections();
  ~vtkGLSPrincipalDirections() override;

  SampleRequest GetSampleRequest(const vtkGLSRun& run) const override;
  int ComputeOutputs(vtkGLSRun& run) override;

  bool ReuseInputScaleSpace;
  double AnisotropyThreshold;
  double DirectionScale;
  int OutputPrecision;

private:
  /// The index of the analysed scale DirectionScale names, -1 when it is 0; -2 (an error reported) when it lies
  /// outside the analysed scales.
  int ChosenScaleIndex(const vtkGLSRun& run);

  vtkGLSPrincipalDirections(const vtkGLSPrincipalDirections&) = delete;
  void operator=(const vtkGLSPrincipalDirections&) = delete;
};

#endif
