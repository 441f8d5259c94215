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
 * Composite inputs (a multiblock of clouds): QueryPointId counts the points of the blocks one after the other (the
 * field data GLSQueryPointId holds that flat id in every block's output); every block is compared with that point;
 * the blocks must have the same scales (relative scales are relative to the whole composite, so they do).
 * Errors: a query id out of range, a query point with non-finite coordinates or without any defined fit inside the
 * prior, a prior range that holds no sampled scale.
 */
#ifndef vtkGLSMultiScaleDissimilarity_h
#define vtkGLSMultiScaleDissimilarity_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSScaleFilterBase.h" // IWYU pragma: keep

#include <memory> // for std::unique_ptr

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
  /// When on (default), tau, kappa and phi come from the GLSTau/GLSKappa/GLSFitness arrays of an upstream
  /// vtkGLSScaleSpace and its GLSScales, and this filter's scale parameters are ignored. Off: always refit.
  vtkSetMacro(ReuseInputScaleSpace, bool);
  vtkGetMacro(ReuseInputScaleSpace, bool);
  vtkBooleanMacro(ReuseInputScaleSpace, bool);
  ///@}

  ///@{
  /// Id of the query point (default 0; a negative id or one past the last point is an error). Ignored when
  /// UseQueryPointCoordinates is on. In a distributed run (several
  /// processes, see vtkGLSScaleFilterBase) it is a global id: the value of the point-data GlobalIds attribute when
  /// the pieces carry one (the serial index when the ids were made before the cloud was split), else the index in
  /// the rank-order concatenation of the pieces; the rank holding it computes its descriptors and broadcasts them.
  /// The field data GLSQueryPointId then holds that global id.
  vtkSetMacro(QueryPointId, vtkIdType);
  vtkGetMacro(QueryPointId, vtkIdType);
  ///@}

  ///@{
  /// Coordinates of the query (snapped to the nearest input point with finite coordinates), used when
  /// UseQueryPointCoordinates is on (default off). Not finite, or farther from every input point than the input's
  /// bounding-box diagonal (not on this cloud): an error.
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
  vtkSetMacro(PriorShape, int);
  vtkGetMacro(PriorShape, int);
  void SetPriorShapeToBox() { this->SetPriorShape(BOX); }
  void SetPriorShapeToLogGaussian() { this->SetPriorShape(LOG_GAUSSIAN); }
  ///@}

  ///@{
  /// Points with Delta < Threshold are marked similar (dimensionless, default 0.01).
  vtkSetMacro(Threshold, double);
  vtkGetMacro(Threshold, double);
  ///@}

protected:
  void DescribeSettings(std::vector<SettingRange>& settings) override;

  vtkGLSMultiScaleDissimilarity();
  ~vtkGLSMultiScaleDissimilarity() override;

  /// Locates the query point (before anything is fitted): an error when it is out of range or there is no point.
  bool CheckParameters(vtkGLSRun& run) override;

  /// A composite input: the query is a point of one block (QueryPointId counts the points of the blocks one after
  /// the other; with UseQueryPointCoordinates, the nearest point of all blocks). That block is run first; the
  /// others are compared with its query's descriptors.
  bool BeginComposite(const std::vector<vtkSmartPointer<vtkPointSet>>& blocks, double diagonal,
    std::vector<std::size_t>& order) override;
  void EndComposite() override;
  SampleRequest GetSampleRequest(const vtkGLSRun& run) const override;
  int ComputeOutputs(vtkGLSRun& run) override;

  struct QueryDescriptors;
  /// The scale prior at the run's scales (PriorShape over [PriorMinScale, PriorMaxScale] clipped to the sampled
  /// range); empty, with an error naming the range given, when no sampled scale lies in it.
  std::vector<double> ResolvePrior(const vtkGLSRun& run);
  /// The query point's descriptors at the run's scales: fitted on the piece that holds it and sent to every rank, or
  /// those of the query's block of a composite input. COMPLETED, ABORTED, or FAILED with an error (no defined fit at
  /// any scale of the prior; blocks at different scales).
  int DescribeQuery(vtkGLSRun& run, const std::vector<double>& prior, QueryDescriptors& descriptors);
  /// GLSDissimilarity and GLSSimilar of every point against the query's descriptors, and GLSQueryPointId.
  int WriteDissimilarity(vtkGLSRun& run, const std::vector<double>& prior, const QueryDescriptors& query);

  /// Distributed run: finds the query over all pieces (by global id, or the nearest point to QueryPoint given this
  /// piece's nearest squared distance `localBest2`), sets `query` to its index in this piece (-1 elsewhere),
  /// `globalId`, and `owner` (the rank whose piece holds it). False (with an error, on every rank) when no piece
  /// has it.
  /// The squared distance from p to QueryPoint over the square of a power of two that keeps it finite wherever
  /// QueryPoint lies (a query at 1e300 is compared without overflow): the order of the input points by it is their
  /// order by distance, the same in a serial and a distributed run. QueryDistanceScale() gives that power of two.
  double QueryDistance2(const double p[3]) const;
  double QueryDistanceScale() const;
  /// With UseQueryPointCoordinates: false, with an error, when QueryPoint is not finite, or when the nearest input
  /// point (at the squared distance `best2` of QueryDistance2) lies farther than the input's diagonal (QueryPoint is
  /// not on this cloud: another frame's coordinates?).
  bool CheckQueryPointIsNear(const vtkGLSRun& run, double best2);
  bool LocateDistributedQuery(const vtkGLSRun& run, vtkIdType wanted, double localBest2, vtkIdType& query,
    long long& globalId, int& owner);

  struct CompositeQuery;
  /// During the run of a composite input only: the query's block and, once it ran, its descriptors.
  std::unique_ptr<CompositeQuery> Composite;

  bool ReuseInputScaleSpace;
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
