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
 *     vtkGLSFilterBase               NumberOfThreads, MemoryBudget, Controller
 *     |- vtkGLSNormalEstimation
 *     `- vtkGLSFitFilterBase         Normals, ScaleUnits, MinimumNeighbors: the cloud to fit
 *        |- vtkGLSProjection
 *        `- vtkGLSScaleFilterBase    the scales, Backend: the samples at every scale
 *           |- vtkGLSScaleSpace, vtkGLSMultiScaleDissimilarity
 *           `- vtkGLSVariationFilterBase   WTau, WEta, WKappa: the geometric variation nu
 *              `- vtkGLSGeometricVariation, vtkGLSContinuousFeatures, vtkGLSAdaptiveBandwidth,
 *                 vtkGLSScaleProfiles, vtkGLSScaleSpaceImage
 *
 * Input: any vtkPointSet (vtkPolyData, vtkUnstructuredGrid, ...; only its points are used), the output has the
 * input's type; or a composite dataset (vtkMultiBlockDataSet, vtkPartitionedDataSet, ...) of point sets, each block
 * computed on its own points with lengths relative to the bounding-box diagonal of the whole composite, the output
 * a composite of the same structure.
 *
 * Coincident points (bitwise-equal coordinates, e.g. an OBJ reader splitting vertices per face corner) are merged:
 * each position is computed and counted once in every neighbourhood and its results are written to every copy; a
 * warning says how many, and the field data GLSCoincidentPoints holds the count.
 *
 * Errors (vtkErrorMacro, RequestData returns 0): an input without points (on every process of a distributed run),
 * and the filters' own. A failed run leaves its outputs empty, so that nothing downstream runs on stale data. An
 * aborted run (AbortExecute, e.g. ParaView's cancel) returns early; its output then carries the input without
 * partial arrays.
 *
 * Distributed runs (pvbatch / pvserver on N MPI ranks): when the Controller has several processes each rank holds a
 * piece of the cloud; every filter then exchanges the points near its piece with the other ranks (ghosts, see
 * vtkGLSDistributedCloud), computes its own points only, and gives the results a serial run gives. A rank may hold no
 * points. See docs/distributed.md.
 */
#ifndef vtkGLSFilterBase_h
#define vtkGLSFilterBase_h

#include "vtkGLSFiltersModule.h"
#include "vtkPointSetAlgorithm.h"
#include "vtkSmartPointer.h" // for the composite hook

#include <cstdint>
#include <string>
#include <vector>

class vtkCompositeDataSet;
class vtkDataArray;
class vtkDataSet;
class vtkFieldData;
class vtkMultiProcessController;
class vtkPointSet;
class vtkGLSDistributedCloud;
struct vtkGLSRun;

class VTKGLSFILTERS_EXPORT vtkGLSFilterBase : public vtkPointSetAlgorithm
{
public:
  vtkTypeMacro(vtkGLSFilterBase, vtkPointSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Worker threads (0 = all hardware threads, the default; at most 1024). Results are bitwise identical for any
  /// value.
  vtkSetMacro(NumberOfThreads, int);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /// Memory this filter may allocate for its outputs and scratch, in MiB (0, the default: half of the physical
  /// memory). Before allocating, the filter estimates what it needs; above the budget it stops with an error that
  /// says how much it needs and what to change, and computes nothing. A filter that takes scales fits the cloud in
  /// spatial tiles, one after the other, when its fitting engine alone would not fit: each tile with the points
  /// within reach of its largest scale, results bit for bit those of one engine (the output field data GLSTiles says
  /// how many). Before tiles, a multi-resolution fit of float32 normals keeps them as given, normalized when read
  /// (12 bytes a point less, the same results bit for bit, a pass about 3% longer: field data GLSCompactNormals).
  vtkSetMacro(MemoryBudget, double);
  vtkGetMacro(MemoryBudget, double);
  ///@}

  ///@{
  /// The controller of a distributed run (default: the global controller when the filter is created, as ParaView's
  /// pvbatch and pvserver set it). Null or a single process: serial.
  virtual void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  /// The allowed range of a numeric setting, by its property name (e.g. "Accuracy"; an enumeration's first and last
  /// values): a value outside it, or NaN, is refused when the filter runs, with an error naming the setting, the value
  /// given and the range (nothing is clamped). NaN for a name the filter does not check this way.
  double GetSettingMinimum(const char* name);
  double GetSettingMaximum(const char* name);

protected:
  /// A numeric setting, its value and its allowed range [Minimum, Maximum].
  struct SettingRange
  {
    const char* Name;
    double Value;
    double Minimum;
    double Maximum;
  };

  /// The filter's range-checked settings: a subclass appends its own to its superclass's (the one place their ranges
  /// are written; the ParaView XML's domains agree, tested).
  virtual void DescribeSettings(std::vector<SettingRange>& settings);

  /// False (with an error naming `needed`, `what` and `advice`) when `needed` bytes exceed the MemoryBudget.
  bool CheckMemoryBudget(double needed, const char* what, const char* advice);

  /// The MemoryBudget in bytes (0 resolved to half of the physical memory).
  double MemoryBudgetBytes() const;

  /// False on every rank when `ok` is false on some rank; a rank that was fine then says why it stopped.
  bool AgreeToContinue(const vtkGLSRun& run, bool ok);

  /// False (with an error naming the setting, the value given and its range) when a setting is outside its range or
  /// NaN. Checked before any work, on every rank alike.
  bool ValidateSettings();

  /// The minimum or maximum of the named setting's range (NaN when the filter has no such setting).
  double SettingBound(const char* name, bool maximum);

  vtkGLSFilterBase();
  ~vtkGLSFilterBase() override;

  /// A vtkPointSet or a composite dataset of point sets.
  int FillInputPortInformation(int port, vtkInformation* info) override;
  /// Any data object: RequestDataObject makes it the input's type.
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  /// The output has the input's type (a composite input gives a composite of the same type).
  int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// For filters whose outputs are not the input's type (a table, an image): makes each output port's data object
  /// of the type its FillOutputPortInformation declares (DATA_TYPE_NAME).
  int MakeDeclaredOutputs(vtkInformationVector* outputVector);

  /// The run: PrepareOutputs, DistributeRun, the checks of the input, then Execute (per block for a composite
  /// input). Filters do not override it.
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// What Execute (and the hooks below it) return.
  enum Outcome
  {
    FAILED = 0,   ///< an error was reported: RequestData returns 0 and the outputs are emptied
    ABORTED = 1,  ///< stopped by AbortExecute: no partial arrays were added
    COMPLETED = 2 ///< the outputs are complete
  };

  /// The filter's work on a started run. Returns an Outcome.
  virtual int Execute(vtkGLSRun& run) = 0;

  /// Makes the outputs of the run. Default: the output (port 0) is the input shallow-copied with its own field data
  /// (run.Output). Filters with other outputs (a table, an image) override it.
  virtual void PrepareOutputs(vtkGLSRun& run);

  /// How the run is distributed. Default: as the Controller says. A filter whose input is never cut into pieces
  /// (a curve) may make the run serial on the rank that holds the input and idle elsewhere (run.Idle). False with
  /// an error otherwise, on every rank alike.
  virtual bool DistributeRun(vtkGLSRun& run);

  /// Called once before the blocks of a composite input are run, each as a run of its own, in `order` (indices
  /// into `blocks`, the composite's leaves; an empty point set stands for a missing leaf): a filter whose
  /// parameters name one block's point (the dissimilarity's query) finds it here and may run its block first.
  /// `diagonal` is the whole composite's. False with an error. Collective.
  virtual bool BeginComposite(
    const std::vector<vtkSmartPointer<vtkPointSet>>& blocks, double diagonal, std::vector<std::size_t>& order);
  /// Called once after the blocks of a composite input were run.
  virtual void EndComposite();

  /// Maps a fraction of the core's work to [begin, end] of this filter's progress; true when the user aborted.
  bool ReportProgress(double fraction, double begin, double end);

  /// The normals a filter uses: the point array selected with SetInputArrayToProcess(index, ...) by name, which
  /// must be a floating-point array of 3 components; or, when none is selected (no name, an empty one, or
  /// "(automatic)"), the active normals, else the one floating-point 3-component array whose name says normals
  /// ("normal" or "nrm" in it, any case). Null with the reason in `problem` otherwise (several candidates, none,
  /// colours, ...); `absent` tells the case where the input has no candidate at all. A selection of the wrong
  /// shape is a problem too. `what` names the array in the problems ("normals", "viewpoint").
  vtkDataArray* SelectNormals(
    int index, vtkDataSet* input, std::string& problem, bool& absent, const char* what = "normals");

  /// Warns (once per run) when the lengths of given normals are far from 1: the count of finite non-zero normals
  /// whose length is off by more than 1e-3 (they are normalized; such a count suggests another array was meant).
  void WarnAboutNormalLengths(const vtkGLSRun& run, const std::vector<double>& normals, const char* name);

  /// The array name selected with SetInputArrayToProcess(index, ...), or null when none (or an empty name, or
  /// "(automatic)").
  const char* SelectedArrayName(int index);

  /// Merges the run's coincident points (vtkGLSCloud::MergeCoincident) and notes how many there were. Collective.
  void MergeCoincidentPoints(vtkGLSRun& run);

  /// Records that `merged` of this piece's input points coincide with another one (run.CoincidentPoints, written to
  /// the field data) and, when some do anywhere, says so in one warning (on rank 0). Collective.
  void NoteCoincidentPoints(vtkGLSRun& run, std::size_t merged);

  /// A progress report at the current fraction between two silent steps of a long run (so that the GUI stays
  /// responsive and an abort is seen); true when the run is to be aborted.
  bool Heartbeat();

  /// Sets the stray points of xyz (3 per point: this rank's piece; vtkGLSDistributedCloud::StrayPoints, judged over
  /// every piece, gls::findStrayPoints in a serial run) to NaN, so that they join no neighbourhood, their results are
  /// NaN and the bounds (the relative scales) are the other points', and lists them in `stray` (increasing). The one
  /// rule of every run's bounds. False on a communication error.
  static bool BlankStrayPoints(
    const vtkGLSDistributedCloud& dist, std::vector<double>& xyz, std::vector<std::uint64_t>& stray);

  /// Writes what the run reports in the output's field data: GLSGhostPoints (the ghosts this rank used, in a
  /// distributed run that exchanged them), GLSStrayPoints (stray points left out, when some were),
  /// GLSNonFinitePoints (points with a non-finite coordinate left out, when some were), GLSTiles (the spatial tiles
  /// of a fit cut to its MemoryBudget, when more than one), GLSCompactNormals (1 where the fit kept its normals compact
  /// to meet the MemoryBudget), GLSCoincidentPoints (points merged into another, when some were) and GLSBackend
  /// (where the fits ran, when a fit ran).
  static void WriteRunFieldData(const vtkGLSRun& run, vtkFieldData* fd);

  /// Copies the first n tuples of `triples` (3 components, any value type) into out (3 n doubles): one block copy
  /// for an array of doubles in one block (vtkDoubleArray), tuple by tuple otherwise. The same values either way.
  static void CopyTriples(vtkDataArray* triples, vtkIdType n, double* out);

  int NumberOfThreads;
  double MemoryBudget;
  vtkMultiProcessController* Controller = nullptr;

private:
  /// One run on a point set (or a composite's block): `diagonal` > 0 replaces the input's own (a composite's).
  int RunOn(vtkPointSet* input, vtkInformationVector* outputVector, vtkDataObject* blockOutput, double diagonal);
  /// Every block of a composite input, with the whole composite's diagonal.
  int RunOnBlocks(vtkCompositeDataSet* input, vtkInformationVector* outputVector);
  /// The diagonal of a composite input's finite points, its stray points left out (every block must be a point set
  /// or empty: false with an error otherwise). Collective.
  bool CompositeDiagonal(vtkCompositeDataSet* input, const vtkGLSDistributedCloud& dist, double& diagonal);
  /// Runs the blocks in `order` (a block without points on every process passes through), their outputs into
  /// `outputs`; `computed` counts the blocks run. The first failure stops the runs and is returned. Collective.
  int RunBlocksInOrder(const vtkGLSDistributedCloud& dist, const std::vector<vtkSmartPointer<vtkPointSet>>& blocks,
    const std::vector<std::size_t>& order, vtkInformationVector* outputVector, double diagonal,
    std::vector<vtkSmartPointer<vtkDataObject>>& outputs, int& computed);

  /// The distributed context, the input's points (run.Cloud, without normals), the check that some process has
  /// points, and the bounds of the whole input.
  bool BeginRun(vtkGLSRun& run);
  /// Makes every row of run.Cloud's owned points with a non-finite coordinate (a scanner's missing return: NaN, or
  /// an infinity) NaN in all three, so that it joins no neighbourhood, no bound and gets NaN results; counts them
  /// (run.NonFinitePoints, written to the field data) and, when some piece has any, says so in one warning (rank 0).
  /// Collective.
  void LeaveOutNonFinitePoints(vtkGLSRun& run);

  vtkGLSFilterBase(const vtkGLSFilterBase&) = delete;
  void operator=(const vtkGLSFilterBase&) = delete;
};

#endif
