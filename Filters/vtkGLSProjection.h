/**
 * @class   vtkGLSProjection
 * @brief   Denoising by MLS projection: moves every point onto the GLS surface of the input cloud.
 *
 * Each point is projected onto the algebraic sphere fitted (with the GLS weight (d^2/t^2 - 1)^2, oriented normals)
 * to the input points within t of it; the sphere is refitted around the new position and the step repeated until
 * it is at most Tolerance * t (at most MaxIterations fits): the iterated MLS projection. The support t is either
 * one Scale for all points or each point's value of a bandwidth array (the GLSBandwidth of
 * vtkGLSAdaptiveBandwidth), see ScaleMode. The neighbourhoods always come from the input points (not the moved
 * ones), so the result does not depend on the order of the points.
 *
 * Output: the input with its points moved (double precision; cells kept) and point arrays `Normals` (eta of the
 * final fit, unit, set as the active normals; replaces an input array of that name), GLSDisplacement (length,
 * distance moved) and GLSProjectionIterations (fits made; MaxIterations means it did not converge). A point with
 * non-finite coordinates, a non-finite or non-positive scale, or an undefined fit on the way (fewer than
 * MinimumNeighbors neighbours, degenerate neighbourhood) keeps its position and (normalized) input normal and gets
 * GLSDisplacement NaN. Field data: GLSBackend ("CPU": the projection runs on the CPU engine).
 *
 * Inputs: points and oriented normals as for every GLS fit (vtkGLSFitFilterBase, SetInputArrayToProcess(0, ...));
 * the bandwidth array is selected with SetInputArrayToProcess(1, ...) (default: the point array GLSBandwidth).
 * Errors: no normals, a missing or mis-sized bandwidth array in BANDWIDTH_ARRAY mode, Scale <= 0 in FIXED_SCALE
 * mode.
 *
 * Distributed runs (see vtkGLSFilterBase): each rank fetches the other ranks' points within twice the largest
 * support of all ranks around its piece, projects its own points, and checks that every one ended within its
 * support of that band (distance moved + t <= band); if not, every rank redoes the projection with the band doubled.
 * The intermediate positions are not checked. Field data GLSGhostPoints: the ghosts of the last pass.
 */
#ifndef vtkGLSProjection_h
#define vtkGLSProjection_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSFitFilterBase.h"

#include <vector> // for std::vector

namespace gls
{
struct ProjectionSettings;
struct ProjectionOutputs;
}
struct vtkGLSCloud;

class VTKGLSFILTERS_EXPORT vtkGLSProjection : public vtkGLSFitFilterBase
{
public:
  static vtkGLSProjection* New();
  vtkTypeMacro(vtkGLSProjection, vtkGLSFitFilterBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ScaleModeType
  {
    AUTOMATIC = 0,       ///< the selected bandwidth array, else GLSBandwidth, when the input has it; else Scale
    FIXED_SCALE = 1,     ///< Scale for every point
    BANDWIDTH_ARRAY = 2  ///< each point's value of the selected bandwidth array (length units)
  };

  ///@{
  /// Where the support of each point comes from (default AUTOMATIC).
  vtkSetMacro(ScaleMode, int);
  vtkGetMacro(ScaleMode, int);
  void SetScaleModeToAutomatic() { this->SetScaleMode(AUTOMATIC); }
  void SetScaleModeToFixedScale() { this->SetScaleMode(FIXED_SCALE); }
  void SetScaleModeToBandwidthArray() { this->SetScaleMode(BANDWIDTH_ARRAY); }
  ///@}

  ///@{
  /// The single support t of FIXED_SCALE mode, in ScaleUnits (default 0.01: 1% of the bounding-box diagonal).
  vtkSetMacro(Scale, double);
  vtkGetMacro(Scale, double);
  ///@}

  ///@{
  /// Fits per point at most (default 50, at least 1: 1 = one projection step, no iteration).
  vtkSetMacro(MaxIterations, int);
  vtkGetMacro(MaxIterations, int);
  ///@}

  ///@{
  /// The iteration stops when a step is at most Tolerance times the point's scale (dimensionless, default 1e-6).
  vtkSetMacro(Tolerance, double);
  vtkGetMacro(Tolerance, double);
  ///@}

  /// The mode the last run used (FIXED_SCALE or BANDWIDTH_ARRAY; AUTOMATIC before any run).
  vtkGetMacro(LastScaleMode, int);

protected:
  void DescribeSettings(std::vector<SettingRange>& settings) override;

  vtkGLSProjection();
  ~vtkGLSProjection() override;

  int Execute(vtkGLSRun& run) override;

  /// Each point's support (`scales`) and the ScaleMode used; false (with an error) on a missing or mis-sized
  /// bandwidth array or a bad Scale.
  bool ResolveSupports(const vtkGLSRun& run, std::vector<double>& scales, int& mode);

  /// Projects every point of the cloud (owned and ghosts) at its scale, each distinct position once when some
  /// coincide (the results go back to every copy). Returns false if aborted.
  static bool ProjectMerged(vtkGLSCloud cloud, const std::vector<double>& scales,
    const gls::ProjectionSettings& settings, const gls::ProjectionOutputs& out);

  /// The distributed projection (see the class documentation): this piece's points (with their supports) projected
  /// with ghosts into `out`. False (with an error) on a communication failure.
  bool ProjectDistributed(vtkGLSRun& run, const std::vector<double>& scales, gls::ProjectionSettings settings,
    const gls::ProjectionOutputs& out);

  int ScaleMode;
  double Scale;
  int MaxIterations;
  double Tolerance;
  int LastScaleMode = AUTOMATIC;

private:
  vtkGLSProjection(const vtkGLSProjection&) = delete;
  void operator=(const vtkGLSProjection&) = delete;
};

#endif
