/**
 * @class   vtkGLSScaleSpaceImage
 * @brief   Scale-space image of a curve (the paper's Figures 6-8): GLS curvature against arclength and scale.
 *
 * Input: a vtkPolyData holding an ordered curve. The order is that of the first line cell (a polyline); with no
 * line cell, the order of the points. Only the points of that cell are used. Inputs made of separate 2-point
 * segments should be joined with vtkStripper first (a first cell with fewer than 3 points is an error).
 * The curve is closed when the polyline's last id equals its first, or as set by Closed (see there).
 *
 * At every curve point the GLS sphere is fitted at NumberOfScales scales (default 200) sampled LINEARLY from
 * MinScale to MaxScale (in ScaleUnits; relative scales are fractions of the input's bounding-box diagonal).
 * ScaleSampling is ignored: the image rows must be equally spaced in t. An explicit scale list (AddScale) is used
 * when given, and must be equally spaced (to 1e-6 of its range), otherwise RequestData fails with an error.
 *
 * Output port 0, a vtkImageData of dimensions (NumberOfArclengthSamples, number of scales, 1): x is the arclength
 * along the curve (length units, origin 0, from 0 to the curve length L), y is the scale t (length units, origin
 * the first scale, spacing the scale step), z one slice. Point-data arrays:
 * - `GLSKappa`: signed GLS curvature (1/length);
 * - `GLSScaledKappa`: t * kappa (dimensionless; the active scalars, the nicer one to colour);
 * - `GLSNu`: geometric variation nu = WTau dtau^2 + WEta t^2 |deta|^2 + WKappa t^4 dkappa^2 (dimensionless).
 * The fits are computed AT THE CURVE POINTS and then resampled: a column at arclength s takes, per scale, the linear
 * interpolation (in arclength) of the values of the two curve points around s (NaN if either is NaN, except at a
 * curve point itself). NaN marks undefined fits (fewer than MinimumNeighbors neighbours in the ball).
 * Field data: `GLSScales` (the absolute scales used) and `GLSBackend` (where the fits ran).
 *
 * Output port 1, a vtkPolyData: the zero crossings of kappa as polylines in the same (arclength, t, 0) frame: the
 * 0-isoline of GLSKappa on the image (vtkContourFilter, then vtkStripper; single-precision points, linear
 * interpolation along the image's cell edges). Segments touching NaN values are dropped.
 *
 * Normals: the array selected with SetInputArrayToProcess(0, ...), by default the active normals. When the input
 * has none and the curve is planar (every point within 1e-6 * diagonal of its best-fit plane), in-plane normals are
 * computed: perpendicular to the tangent p(i+1) - p(i-1) (one-sided at the ends of an open curve), in the plane,
 * and oriented consistently along the traversal: outward for a closed curve; for an open curve to the LEFT of the
 * traversal direction w.r.t. the plane normal, which is taken as the unit normal of the best-fit plane whose
 * largest-magnitude component is positive (+z for a curve in a plane z = const). With these conventions
 * kappa = +1/r on a circle, and on the open curve y = A sin x traversed with increasing x,
 * kappa(x) = +A sin x / (1 + A^2 cos^2 x)^(3/2) (kappa > 0 where the curve turns clockwise).
 * Planar curves are fitted in the coordinates of their plane (rotated so that z = 0; given normals are rotated alike
 * and their out-of-plane part dropped when below 1e-9 of their length), so a 2D fit with MinimumNeighbors 3 runs and
 * the image does not depend on the plane's orientation. A non-planar curve needs normals: it is fitted in 3D.
 *
 * Errors (vtkErrorMacro, RequestData returns 0): fewer than 3 curve points, non-finite coordinates, a zero-length
 * curve, a non-planar curve without normals, mis-sized normals, unequally spaced explicit scales, and the scale
 * errors of vtkGLSScaleFilterBase. Progress is reported; an aborted run leaves both outputs empty.
 * The filter always fits its own scales (upstream arrays are never reused).
 *
 * Distributed runs (several MPI processes, see vtkGLSScaleFilterBase): the curve must be on one process (a curve
 * source that ignores piece requests puts it on rank 0); that process computes the image as a serial run would and
 * the others give empty outputs. A curve spread over several processes is an error.
 */
#ifndef vtkGLSScaleSpaceImage_h
#define vtkGLSScaleSpaceImage_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSVariationFilterBase.h"

class vtkImageData;

class VTKGLSFILTERS_EXPORT vtkGLSScaleSpaceImage : public vtkGLSVariationFilterBase
{
public:
  static vtkGLSScaleSpaceImage* New();
  vtkTypeMacro(vtkGLSScaleSpaceImage, vtkGLSVariationFilterBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ClosedType
  {
    CLOSED_AUTO = 0, ///< closed when the polyline's last id equals its first, or its end points coincide (1e-9 diag)
    CLOSED_OPEN = 1, ///< always open (a repeated last id is then dropped, the end points are not joined)
    CLOSED_YES = 2   ///< always closed: a segment joins the last point to the first
  };

  ///@{
  /// Whether the curve is closed (default CLOSED_AUTO). A closed curve's arclength runs from 0 to its full length
  /// L, including the closing segment; the image column at s = L then repeats the one at s = 0.
  vtkSetMacro(Closed, int);
  vtkGetMacro(Closed, int);
  void SetClosedToAuto() { this->SetClosed(CLOSED_AUTO); }
  void SetClosedToOpen() { this->SetClosed(CLOSED_OPEN); }
  void SetClosedToClosed() { this->SetClosed(CLOSED_YES); }
  ///@}

  ///@{
  /// Number of image columns, uniformly spaced in arclength from 0 to L (both included); default 1000, at least 2
  /// when set. 0 = one per curve point (plus one for a closed curve, for s = L): the image's extent is then known
  /// at RequestInformation only when the input data is already there (SetInputData); downstream of a reader or
  /// filter it is not, and a consumer that asks for the whole extent beforehand (ParaView's representations) gets
  /// an empty image.
  vtkSetMacro(NumberOfArclengthSamples, int);
  vtkGetMacro(NumberOfArclengthSamples, int);
  ///@}

  /// Was the last curve closed (after CLOSED_AUTO detection)? Its length (input units)?
  vtkGetMacro(LastCurveClosed, bool);
  vtkGetMacro(LastCurveLength, double);

  /// Output port 0: the scale-space image.
  vtkImageData* GetImageOutput();
  /// Output port 1: the zero crossings of kappa as polylines in (arclength, t, 0).
  vtkPolyData* GetCrossingsOutput();

protected:
  void DescribeSettings(std::vector<SettingRange>& settings) override;

  vtkGLSScaleSpaceImage();
  ~vtkGLSScaleSpaceImage() override;

  /// A vtkPolyData (a composite input is run block by block by the pipeline).
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  /// A vtkImageData and a vtkPolyData.
  int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// Announces the image's extent when the input is at hand.
  int ExecuteInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// The outputs (an image and polylines) are made from nothing of the input.
  void PrepareOutputs(vtkGLSRun& run) override;
  /// Distributed runs: the rank holding the whole curve computes as a serial run, the others stay idle.
  bool DistributeRun(vtkGLSRun& run) override;
  /// Extracts the curve (its errors come first) and sets it as the cloud to fit.
  bool CheckParameters(vtkGLSRun& run) override;
  SampleRequest GetSampleRequest(const vtkGLSRun& run) const override;
  /// Linear scales; an explicit list must be equally spaced.
  bool ResolveScales(vtkGLSRun& run) override;
  /// The curve's points and normals, planar curves in their plane's coordinates (z = 0).
  bool GatherFitCloud(vtkGLSRun& run) override;
  int ComputeOutputs(vtkGLSRun& run) override;

  int Closed;
  int NumberOfArclengthSamples;
  bool LastCurveClosed = false;
  double LastCurveLength = 0.0;

private:
  vtkGLSScaleSpaceImage(const vtkGLSScaleSpaceImage&) = delete;
  void operator=(const vtkGLSScaleSpaceImage&) = delete;
};

#endif
