/**
 * @class   vtkGLSScaleProfiles
 * @brief   GLS scale profiles of selected points: a table of descriptors against finely sampled scales.
 *
 * For each selected point (AddPointId), fits the GLS sphere at NumberOfScales scales (default 200, from MinScale to
 * MaxScale with ScaleSampling, see vtkGLSScaleFilterBase; all from one gather of the point's neighbours) and writes
 * one row per scale: column `t` (the scale, length) and, per point id N, the dimensionless profiles of the paper's
 * Figures 2-3: `tau/t (N)`, `t*kappa (N)`, `phi (N)` and `nu (N)` (the geometric variation with weights WTau, WEta,
 * WKappa). NaN where the fit is undefined. The output is a vtkTable, shown in ParaView's line chart view.
 * The profiles always sample their own scales: ReuseInputScaleSpace is ignored (upstream arrays are never reused).
 * Errors: no point selected, a point id out of range, and the errors of vtkGLSScaleFilterBase.
 */
#ifndef vtkGLSScaleProfiles_h
#define vtkGLSScaleProfiles_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSScaleFilterBase.h"

#include <vector>

class vtkTable;

class VTKGLSFILTERS_EXPORT vtkGLSScaleProfiles : public vtkGLSScaleFilterBase
{
public:
  static vtkGLSScaleProfiles* New();
  vtkTypeMacro(vtkGLSScaleProfiles, vtkGLSScaleFilterBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The points whose profiles are computed (ids into the input's points).
  void AddPointId(vtkIdType id);
  void RemoveAllPointIds();
  int GetNumberOfPointIds() const { return static_cast<int>(this->PointIds.size()); }
  ///@}

  /// The output table.
  vtkTable* GetOutputTable();

protected:
  vtkGLSScaleProfiles();
  ~vtkGLSScaleProfiles() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  bool AcceptsStoredScaleSpace() const override { return false; }
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::vector<vtkIdType> PointIds;

private:
  vtkGLSScaleProfiles(const vtkGLSScaleProfiles&) = delete;
  void operator=(const vtkGLSScaleProfiles&) = delete;
};

#endif
