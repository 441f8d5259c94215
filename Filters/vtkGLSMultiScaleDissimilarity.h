/**
 * @class   vtkGLSMultiScaleDissimilarity
 * @brief   Multi-scale GLS dissimilarity of every point to a picked query point, and the points similar to it.
 *
 * Delta(p, q) = sum_i delta_{p,q}(t_i) h_i (Mellado et al. 2012, sec. 5) with the per-scale dissimilarity
 * delta = (tau_p/t - tau_q/t)^2 + (t kappa_p - t kappa_q)^2 + (phi_p - phi_q)^2 (eq. 6; eta is left out on purpose,
 * so the measure is invariant to rotation) and h the scale prior: a box over [PriorMinScale, PriorMaxScale] (default
 * every scale; PriorMaxScale 0 = no upper limit) or a Gaussian in ln t centred in that range (standard deviation a
 * quarter of its log width), both normalized to sum 1. Scales where either fit is undefined are left out and h is renormalized over the rest.
 *
 * tau, kappa and phi come from upstream GLSTau/GLSKappa/GLSFitness arrays when present (see ReuseInputScaleSpace),
 * else they are computed here in a fused pass (memory O(N)). The query point is QueryPointId, or, with
 * UseQueryPointCoordinates, the input point nearest to QueryPoint.
 *
 * Point-data outputs: GLSDissimilarity (dimensionless, >= 0; 0 at the query point; NaN where no scale of the prior
 * has both fits defined) and GLSSimilar (unsigned char: 1 where GLSDissimilarity < Threshold, else 0). Field data:
 * GLSQueryPointId (the query point used) and GLSScales (length).
 * Errors: a query id out of range, a query point with non-finite coordinates or without any defined fit inside the
 * prior, a prior range that holds no sampled scale.
 */
#ifndef vtkGLSMultiScaleDissimilarity_h
#define vtkGLSMultiScaleDissimilarity_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSScaleFilterBase.h"

class VTKGLSFILTERS_EXPORT vtkGLSMultiScaleDissimilarity : public vtkGLSScaleFilterBase
{
public:
  static vtkGLSMultiScaleDissimilarity* New();
  vtkTypeMacro(vtkGLSMultiScaleDissimilarity, vtkGLSScaleFilterBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum PriorShapeType
  {
    BOX = 0,         ///< h = 1 inside [PriorMinScale, PriorMaxScale]
    LOG_GAUSSIAN = 1 ///< Gaussian in ln t over that range
  };

  ///@{
  /// Id of the query point (default 0). Ignored when UseQueryPointCoordinates is on.
  vtkSetClampMacro(QueryPointId, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(QueryPointId, vtkIdType);
  ///@}

  ///@{
  /// Coordinates of the query (snapped to the nearest input point with finite coordinates), used when
  /// UseQueryPointCoordinates is on (default off).
  vtkSetVector3Macro(QueryPoint, double);
  vtkGetVector3Macro(QueryPoint, double);
  vtkSetMacro(UseQueryPointCoordinates, bool);
  vtkGetMacro(UseQueryPointCoordinates, bool);
  vtkBooleanMacro(UseQueryPointCoordinates, bool);
  ///@}

  ///@{
  /// Range of the scale prior, in ScaleUnits (defaults 0 and 0; PriorMaxScale = 0 means no upper limit: every
  /// sampled scale). Clipped to the sampled range.
  vtkSetMacro(PriorMinScale, double);
  vtkGetMacro(PriorMinScale, double);
  vtkSetMacro(PriorMaxScale, double);
  vtkGetMacro(PriorMaxScale, double);
  ///@}

  ///@{
  /// Shape of the scale prior (default BOX, the paper's choice).
  vtkSetClampMacro(PriorShape, int, BOX, LOG_GAUSSIAN);
  vtkGetMacro(PriorShape, int);
  void SetPriorShapeToBox() { this->SetPriorShape(BOX); }
  void SetPriorShapeToLogGaussian() { this->SetPriorShape(LOG_GAUSSIAN); }
  ///@}

  ///@{
  /// Points with Delta < Threshold are marked similar (dimensionless, default 0.01).
  vtkSetClampMacro(Threshold, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Threshold, double);
  ///@}

protected:
  vtkGLSMultiScaleDissimilarity();
  ~vtkGLSMultiScaleDissimilarity() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkIdType QueryPointId;
  double QueryPoint[3];
  bool UseQueryPointCoordinates;
  double PriorMinScale;
  double PriorMaxScale;
  int PriorShape;
  double Threshold;

private:
  vtkGLSMultiScaleDissimilarity(const vtkGLSMultiScaleDissimilarity&) = delete;
  void operator=(const vtkGLSMultiScaleDissimilarity&) = delete;
};

#endif
