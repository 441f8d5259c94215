/**
 * @class   vtkGLSScaleProfiles
 * @brief   GLS scale profiles of selected points: a table of descriptors against finely sampled scales.
 *
 * For each selected point (AddPointId), fits the GLS sphere at NumberOfScales scales (default 200, from MinScale to
 * MaxScale with ScaleSampling, see vtkGLSScaleFilterBase; all from one gather of the point's neighbours) and writes
 * one row per scale: column `t` (the scale, length) and, per point id N, the dimensionless profiles of the paper's
 * Figures 2-3: `tau/t (N)`, `t*kappa (N)`, `phi (N)` and `nu (N)` (the geometric variation with weights WTau, WEta,
 * WKappa). NaN where the fit is undefined. The output is a vtkTable, shown in ParaView's line chart view.
 * The profiles always sample their own scales (upstream arrays are never reused).
 * Errors: no point selected, a point id out of range, and the errors of vtkGLSScaleFilterBase.
 * Distributed runs (see vtkGLSScaleFilterBase): the point ids are global ids (the GlobalIds attribute, else the
 * rank-order numbering of the pieces); each rank profiles the selected points it holds (with its ghosts) and the
 * table is assembled on rank 0 (the other ranks output an empty table).
 */
#ifndef vtkGLSScaleProfiles_h
#define vtkGLSScaleProfiles_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSVariationFilterBase.h"

#include <cstddef> // for std::size_t
#include <cstdint> // for std::uint64_t
#include <vector>

class vtkTable;
namespace gls
{
template <typename T>
struct ScaleSampleT;
using ScaleSample = ScaleSampleT<double>;
}

class VTKGLSFILTERS_EXPORT vtkGLSScaleProfiles : public vtkGLSVariationFilterBase
{
public:
  static vtkGLSScaleProfiles* New();
  vtkTypeMacro(vtkGLSScaleProfiles, vtkGLSVariationFilterBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The points whose profiles are computed (ids into the input's points; global ids in a distributed run).
  void AddPointId(vtkIdType id);
  void RemoveAllPointIds();
  int GetNumberOfPointIds() const { return static_cast<int>(this->PointIds.size()); }
  ///@}

  /// The output table.
  vtkTable* GetOutputTable();

protected:
  vtkGLSScaleProfiles();
  ~vtkGLSScaleProfiles() override;

  /// A vtkPointSet (a composite input is run block by block by the pipeline).
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  /// A vtkTable.
  int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// The output is a table: nothing of the input is copied.
  void PrepareOutputs(vtkGLSRun& run) override;
  /// Locates the selected points (before anything is fitted): an error when none is selected or one is out of range.
  bool CheckParameters(vtkGLSRun& run) override;
  SampleRequest GetSampleRequest(const vtkGLSRun& run) const override;
  int ComputeOutputs(vtkGLSRun& run) override;

  /// This piece's indices of the selected points it holds (`ids`) and their positions in PointIds (`slots`).
  /// False (with an error, on every rank) when a selected id is out of range (on every piece).
  bool LocateSelectedPoints(
    const vtkGLSRun& run, std::vector<std::uint64_t>& ids, std::vector<std::size_t>& slots);

  /// The samples of every selected point in PointIds order (S per point) from this piece's (`mine`, in `slots`
  /// order): a copy, or in a distributed run a gather on rank 0 (the other ranks' `samples` are then meaningless).
  bool CollectSamples(const vtkGLSRun& run, const std::vector<gls::ScaleSample>& mine,
    const std::vector<std::size_t>& slots, std::size_t S, std::vector<gls::ScaleSample>& samples);

  std::vector<vtkIdType> PointIds;

private:
  vtkGLSScaleProfiles(const vtkGLSScaleProfiles&) = delete;
  void operator=(const vtkGLSScaleProfiles&) = delete;
};

#endif
