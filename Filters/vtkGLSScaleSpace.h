/**
 * @class   vtkGLSScaleSpace
 * @brief   Growing Least Squares scale space: the algebraic sphere fitted at every point and every scale.
 *
 * For each input point p and each scale t (see vtkGLSScaleFilterBase for the scales, vtkGLSFitFilterBase for the
 * units and normals), fits an
 * oriented algebraic sphere to the neighbours within distance t with the weight (d^2/t^2 - 1)^2 (Mellado et al.,
 * SGP 2012), Pratt-normalized, and its exact analytic derivatives in t. All scales of a point come from one gather
 * of its neighbours (moment formulation), in double precision and local coordinates.
 *
 * Point-data outputs (one component per scale, named "t=<scale>"; 3-vector arrays scale-major: x, y, z of t_0,
 * then of t_1, ...; the list is the descriptor table of docs/filters.md):
 * - GLSTau (length): signed offset from p to the fitted surface, positive on the side the normals point to.
 * - GLSEta (3 per scale, unit): normal of the fitted field at p.
 * - GLSKappa (1/length): signed curvature, 1/radius, positive for a sphere with outward normals, 0 for a plane.
 * - GLSFitness (dimensionless, [0, 1]): the paper's phi (Ponca's fitness() is 1 - phi).
 * - GLSdTau (dimensionless), GLSdEta (1/length, 3 per scale), GLSdKappa (1/length^2): derivatives in t.
 * - GLSNeighborCount (integer): neighbours strictly inside the ball of radius t.
 * - GLSKappaMedian (1/length, one component, the active scalars; with StoreKappa): the median of kappa over the
 *   scales where the fit is defined, NaN where none is: a summary that colours well (a colour map of GLSKappa's
 *   magnitude is NaN wherever a single scale is undefined).
 * With StorePrincipalCurvatures (off by default; any Evaluation, on the CPU):
 * the principal curvatures and directions of the fit (the derivative of its normal field over positions, docs/math.md)
 * - GLSK1 >= GLSK2 (1/length): principal curvatures, positive on a sphere with outward normals.
 * - GLSPrincipalDirection1, GLSPrincipalDirection2 (3 per scale, unit): their tangent directions (d1's largest
 *   component positive, d2 = eta x d1); NaN at an umbilic (k1 - k2 <= 1e-6 / t).
 * - GLSMeanCurvature (1/length, (k1 + k2) / 2), GLSGaussianCurvature (1/length^2, k1 k2), GLSShapeIndex
 *   (dimensionless in [-1, 1], Koenderink's; NaN where flat at the scale), GLSCurvedness (1/length).
 * Field data: GLSScales, the absolute scales (length).
 * A fit that is undefined (fewer than MinimumNeighbors neighbours, all normals cancelling, non-finite point) is NaN
 * in every output for that point and scale.
 */
#ifndef vtkGLSScaleSpace_h
#define vtkGLSScaleSpace_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSScaleFilterBase.h"

class VTKGLSFILTERS_EXPORT vtkGLSScaleSpace : public vtkGLSScaleFilterBase
{
public:
  static vtkGLSScaleSpace* New();
  vtkTypeMacro(vtkGLSScaleSpace, vtkGLSScaleFilterBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Which arrays to write (all on by default); turn off those you do not need to save memory.
  /// StoreDerivatives covers GLSdTau, GLSdEta and GLSdKappa.
  vtkSetMacro(StoreTau, bool);
  vtkGetMacro(StoreTau, bool);
  vtkBooleanMacro(StoreTau, bool);
  vtkSetMacro(StoreEta, bool);
  vtkGetMacro(StoreEta, bool);
  vtkBooleanMacro(StoreEta, bool);
  vtkSetMacro(StoreKappa, bool);
  vtkGetMacro(StoreKappa, bool);
  vtkBooleanMacro(StoreKappa, bool);
  vtkSetMacro(StoreFitness, bool);
  vtkGetMacro(StoreFitness, bool);
  vtkBooleanMacro(StoreFitness, bool);
  vtkSetMacro(StoreDerivatives, bool);
  vtkGetMacro(StoreDerivatives, bool);
  vtkBooleanMacro(StoreDerivatives, bool);
  vtkSetMacro(StoreNeighborCount, bool);
  vtkGetMacro(StoreNeighborCount, bool);
  vtkBooleanMacro(StoreNeighborCount, bool);
  ///@}

  ///@{
  /// Also compute and write the principal curvatures and directions at every scale (off by default: 12 more values
  /// per point and scale; the exact fit takes about 1.6 times as long): GLSK1, GLSK2, GLSPrincipalDirection1,
  /// GLSPrincipalDirection2, GLSMeanCurvature, GLSGaussianCurvature, GLSShapeIndex, GLSCurvedness. Any Evaluation (the
  /// multi-resolution one keeps the curvatures' cell sums too); on the CPU (Backend CUDA falls back with a warning).
  vtkSetMacro(StorePrincipalCurvatures, bool);
  vtkGetMacro(StorePrincipalCurvatures, bool);
  vtkBooleanMacro(StorePrincipalCurvatures, bool);
  ///@}

  enum OutputPrecisionType
  {
    DOUBLE = 0, ///< vtkDoubleArray outputs (default)
    FLOAT = 1   ///< vtkFloatArray outputs: half the memory; the fits are still computed in double
  };

  ///@{
  /// Precision of the stored per-scale arrays (default DOUBLE).
  vtkSetMacro(OutputPrecision, int);
  vtkGetMacro(OutputPrecision, int);
  void SetOutputPrecisionToDouble() { this->SetOutputPrecision(DOUBLE); }
  void SetOutputPrecisionToFloat() { this->SetOutputPrecision(FLOAT); }
  ///@}

protected:
  void DescribeSettings(std::vector<SettingRange>& settings) override;

  vtkGLSScaleSpace();
  ~vtkGLSScaleSpace() override;

  /// The producer of a scale space: it always fits, and its outputs are every stored descriptor.
  SampleRequest GetSampleRequest(const vtkGLSRun& run) const override;
  int ComputeOutputs(vtkGLSRun& run) override;

  /// Whether the given Store switch (vtkGLSDescriptors::Switch) is on.
  bool IsStored(int storeSwitch) const;

  bool StoreTau;
  bool StoreEta;
  bool StoreKappa;
  bool StoreFitness;
  bool StoreDerivatives;
  bool StoreNeighborCount;
  bool StorePrincipalCurvatures;
  int OutputPrecision;

private:
  vtkGLSScaleSpace(const vtkGLSScaleSpace&) = delete;
  void operator=(const vtkGLSScaleSpace&) = delete;
};

#endif
