/**
 * @class   vtkGLSFitFilterBase
 * @brief   The GLS filters that fit spheres to points and normals: the normals to use, the units of lengths, the
 *          smallest neighbourhood of a fit and the memory budget.
 *
 * A GLS fit at a point and scale t is an oriented algebraic sphere fitted to the neighbours within distance t with
 * the weight (d^2/t^2 - 1)^2 (Mellado et al., SGP 2012; docs/math.md). Inputs: a vtkPolyData (only its points are
 * used) with oriented normals: the point array selected with SetInputArrayToProcess(0, ...), by default the active
 * normals (run vtkGLSNormalEstimation first if there are none). Normals need not be unit (they are normalized);
 * points with non-finite coordinates or with zero or non-finite normals are left out of every neighbourhood; points
 * with non-finite coordinates get NaN results. Missing or mis-sized normals are an error.
 *
 * Distributed runs: each rank fetches the other ranks' points (with their normals) within the reach of its fits
 * around its piece (ghosts); the diagonal of relative lengths and the automatic MinimumNeighbors are those of the
 * whole input.
 */
#ifndef vtkGLSFitFilterBase_h
#define vtkGLSFitFilterBase_h

#include "vtkGLSFilterBase.h"
#include "vtkGLSFiltersModule.h"

class VTKGLSFILTERS_EXPORT vtkGLSFitFilterBase : public vtkGLSFilterBase
{
public:
  vtkTypeMacro(vtkGLSFitFilterBase, vtkGLSFilterBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ScaleUnitsType
  {
    ABSOLUTE = 0,            ///< lengths in the input's units
    RELATIVE_TO_DIAGONAL = 1 ///< fractions of the bounding-box diagonal of the input's finite points
  };

  ///@{
  /// How this filter's lengths (scales, supports, radii) are given. Default RELATIVE_TO_DIAGONAL. In a distributed
  /// run the diagonal is the whole input's.
  vtkSetMacro(ScaleUnits, int);
  vtkGetMacro(ScaleUnits, int);
  void SetScaleUnitsToAbsolute() { this->SetScaleUnits(ABSOLUTE); }
  void SetScaleUnitsToRelativeToDiagonal() { this->SetScaleUnits(RELATIVE_TO_DIAGONAL); }
  ///@}

  ///@{
  /// Fits with fewer neighbours strictly inside the ball are NaN. 0 (default) = automatic: 6 for 3D input, 3 for a
  /// 2D curve (every point that takes part in the fits lies in one plane z = const and has its normal in it).
  /// Otherwise at least 3, the floor that keeps a fit determined (1, 2 or a negative value is an error). The output's
  /// field data GLSMinimumNeighbors holds the minimum applied.
  vtkSetMacro(MinimumNeighbors, int);
  vtkGetMacro(MinimumNeighbors, int);
  ///@}

protected:
  void DescribeSettings(std::vector<SettingRange>& settings) override;

  vtkGLSFitFilterBase();
  ~vtkGLSFitFilterBase() override;

  /// False (with an error naming the property) when MinimumNeighbors is invalid.
  bool CheckFitParameters();

  /// Converts a length given in ScaleUnits into an absolute length for this run's input.
  double ToAbsoluteLength(const vtkGLSRun& run, double value) const;

  /// Adds the selected normals of this piece's points to run.Cloud. False (with an error) when they are missing or
  /// mis-sized. Not collective.
  bool GatherNormals(vtkGLSRun& run);

  /// Sets run.MinimumNeighbors (see MinimumNeighbors) from this piece's cloud, before its ghosts are added.
  /// Collective: the 2D decision is the whole input's.
  void ResolveMinimumNeighbors(vtkGLSRun& run) const;

  /// Appends to run.Cloud the other ranks' points and normals within `reach` of this piece (nothing in a serial
  /// run) and records their number in run.GhostPoints. Collective; false (with an error) when the exchange fails.
  bool AddGhosts(vtkGLSRun& run, double reach);

  int ScaleUnits;
  int MinimumNeighbors;

private:
  vtkGLSFitFilterBase(const vtkGLSFitFilterBase&) = delete;
  void operator=(const vtkGLSFitFilterBase&) = delete;
};

#endif
