// What one execution of a GLS filter works with (private to the module). The bases build it step by step --
// vtkGLSFilterBase the outputs, the distributed context and the extent of the input; vtkGLSFitFilterBase the cloud
// to fit; vtkGLSScaleFilterBase the scales and where the samples come from -- then the filter computes its arrays
// from it. It lives for one RequestData: nothing of a run is kept in the filter's members.
#ifndef vtkGLSRun_h
#define vtkGLSRun_h

#include "vtkGLSCloud.h"
#include "vtkGLSDistributedCloud.h"
#include "vtkGLSSampleSource.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

class vtkDataArray;
class vtkInformationVector;
class vtkDataObject;
class vtkPointSet;

/// What a filter keeps of its own for one run, between its hooks (e.g. the dissimilarity's query point).
struct vtkGLSRunState
{
  virtual ~vtkGLSRunState() = default;
};

struct vtkGLSRun
{
  explicit vtkGLSRun(vtkMultiProcessController* controller)
    : Distributed(controller)
  {
  }

  // Built by vtkGLSFilterBase.
  vtkGLSDistributedCloud Distributed;    ///< the collective steps (serial identities in a serial run)
  vtkPointSet* Input = nullptr;          ///< the input (a composite input: one of its blocks)
  vtkInformationVector* OutputVector = nullptr;
  vtkDataObject* OutputObject = nullptr; ///< what port 0 writes to (a composite input: the block's output)
  vtkPointSet* Output = nullptr;         ///< point-data filters: the input with this filter's arrays added
  bool Idle = false;                     ///< this rank takes no part in the run (its outputs stay empty)
  bool HasFinitePoints = false;          ///< some point of the whole (distributed) input has finite coordinates
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 }; ///< of the finite points of the whole input (when HasFinitePoints)
  double Diagonal = 0.0;                 ///< length of the diagonal of Bounds (0 without finite points); for a
                                         ///< composite's block, the whole composite's

  vtkGLSCloud Cloud;                     ///< the input's points; the fit filters add the normals (and the ghosts)

  // Built by vtkGLSFitFilterBase.
  double MinimumNeighbors = 0.0;         ///< resolved (see vtkGLSFitFilterBase::MinimumNeighbors)
  std::string NormalsName;               ///< the name of the normals array used

  // Built by vtkGLSScaleFilterBase.
  std::vector<double> Scales;            ///< absolute scales (length)
  std::unique_ptr<vtkGLSSampleSource> Samples; ///< a fit of the cloud, or the arrays of an upstream scale space
  vtkDataArray* StoredVariation = nullptr; ///< an upstream GLSGeometricVariation at Scales, when it can be used

  // The filter's own.
  std::unique_ptr<vtkGLSRunState> State;

  // Reported in the output's field data (vtkGLSFilterBase::WriteRunFieldData).
  std::string BackendUsed;               ///< where the fits ran ("" when none ran)
  std::string EvaluationUsed;            ///< how the fits evaluated the moments ("" when none ran)
  double AccuracyUsed = 0.0;             ///< epsilon of a multi-resolution fit
  long long GhostPoints = -1;            ///< ghosts this rank used (-1: no exchange)
  long long TilesUsed = 0;               ///< spatial tiles of this rank's fit (0: no fit ran)
  bool CompactNormals = false;           ///< the fit's pyramid kept its normals compact (to meet MemoryBudget)
  long long CoincidentPoints = 0;        ///< this piece's input points merged into another
  long long NonFinitePoints = 0;         ///< this piece's input points with a non-finite coordinate (left out)
  std::vector<std::uint64_t> StrayIds;   ///< stray points of this piece left out, increasing (BlankStrayPoints)
  bool AnyStray = false;                 ///< some piece left stray points out (every rank then marks GLSStray)
};

#endif
