/**
 * @class   vtkGLSFilterBase
 * @brief   What every GLS filter shares: the run of RequestData, the worker threads and the distributed controller.
 *
 * The base owns RequestData (the template method of VTK's vtkPointCloudFilter): it prepares the outputs (by default
 * the output is the input, shallow-copied with its own field data, to which the filter adds its arrays), starts the
 * run -- the distributed context, the check that some process has points, the bounds of the finite points of the
 * whole input -- and hands the run (vtkGLSRun, private) to Execute, which the family bases and the filters
 * implement:
 *
 *     vtkGLSFilterBase               NumberOfThreads, Controller
 *     |- vtkGLSNormalEstimation
 *     `- vtkGLSFitFilterBase         Normals, ScaleUnits, MinimumNeighbors, MemoryBudget: the cloud to fit
 *        |- vtkGLSProjection
 *        `- vtkGLSScaleFilterBase    the scales, Backend: the samples at every scale
 *           |- vtkGLSScaleSpace, vtkGLSMultiScaleDissimilarity
 *           `- vtkGLSVariationFilterBase   WTau, WEta, WKappa: the geometric variation nu
 *              `- vtkGLSGeometricVariation, vtkGLSContinuousFeatures, vtkGLSAdaptiveBandwidth,
 *                 vtkGLSScaleProfiles, vtkGLSScaleSpaceImage
 *
 * Errors: an input without points (on every process of a distributed run) is an error (vtkErrorMacro, RequestData
 * returns 0). An aborted run (AbortExecute, e.g. ParaView's cancel) returns early; its output then carries the input
 * without partial arrays.
 *
 * Distributed runs (pvbatch / pvserver on N MPI ranks): when the Controller has several processes each rank holds a
 * piece of the cloud; every filter then exchanges the points near its piece with the other ranks (ghosts, see
 * vtkGLSDistributedCloud), computes its own points only, and gives the results a serial run gives. A rank may hold no
 * points. See docs/distributed.md.
 */
#ifndef vtkGLSFilterBase_h
#define vtkGLSFilterBase_h

#include "vtkGLSFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

class vtkDataArray;
class vtkFieldData;
class vtkMultiProcessController;
class vtkPolyData;
struct vtkGLSRun;

class VTKGLSFILTERS_EXPORT vtkGLSFilterBase : public vtkPolyDataAlgorithm
{
public:
  vtkTypeMacro(vtkGLSFilterBase, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Worker threads (0 = all hardware threads, the default). Results are bitwise identical for any value.
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /// The controller of a distributed run (default: the global controller when the filter is created, as ParaView's
  /// pvbatch and pvserver set it). Null or a single process: serial.
  virtual void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

protected:
  vtkGLSFilterBase();
  ~vtkGLSFilterBase() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  /// The run: PrepareOutputs, DistributeRun, the checks of the input, then Execute. Filters do not override it.
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// What Execute (and the hooks below it) return.
  enum Outcome
  {
    FAILED = 0,   ///< an error was reported: RequestData returns 0
    ABORTED = 1,  ///< stopped by AbortExecute: no partial arrays were added
    COMPLETED = 2 ///< the outputs are complete
  };

  /// The filter's work on a started run. Returns an Outcome.
  virtual int Execute(vtkGLSRun& run) = 0;

  /// Makes the outputs of the run. Default: the output (port 0, a vtkPolyData) is the input shallow-copied with
  /// its own field data (run.Output). Filters with other outputs (a table, an image) override it.
  virtual void PrepareOutputs(vtkGLSRun& run);

  /// How the run is distributed. Default: as the Controller says. A filter whose input is never cut into pieces
  /// (a curve) may make the run serial on the rank that holds the input and idle elsewhere (run.Idle). False with
  /// an error otherwise, on every rank alike.
  virtual bool DistributeRun(vtkGLSRun& run);

  /// Maps a fraction of the core's work to [begin, end] of this filter's progress; true when the user aborted.
  bool ReportProgress(double fraction, double begin, double end);

  /// The point array selected with SetInputArrayToProcess(index, ...): the named array, or the active normals when
  /// no name (or an empty one, as ParaView sets before it knows the input's arrays) is selected. Null when absent.
  vtkDataArray* FindSelectedNormals(int index, vtkPolyData* input);

  /// The array name selected with SetInputArrayToProcess(index, ...), or null when none (or an empty name).
  const char* SelectedArrayName(int index);

  /// Writes what the run reports in the output's field data: GLSGhostPoints (the ghosts this rank used, in a
  /// distributed run that exchanged them) and GLSBackend (where the fits ran, when a fit ran).
  static void WriteRunFieldData(const vtkGLSRun& run, vtkFieldData* fd);

  int NumberOfThreads;
  vtkMultiProcessController* Controller = nullptr;

private:
  /// The distributed context, the input's points (run.Cloud, without normals), the check that some process has
  /// points, and the bounds of the whole input.
  bool BeginRun(vtkGLSRun& run);

  vtkGLSFilterBase(const vtkGLSFilterBase&) = delete;
  void operator=(const vtkGLSFilterBase&) = delete;
};

#endif
