/**
 * @class   vtkGLSScaleFilterBase
 * @brief   Common parameters and plumbing of the Growing Least Squares filters that work over a range of scales.
 *
 * A scale t is the radius of the compact weight (d^2/t^2 - 1)^2 of the GLS fit, a length. The scales are either an
 * explicit list (AddScale) or NumberOfScales values from MinScale to MaxScale with the chosen ScaleSampling. With
 * ScaleUnits = RELATIVE_TO_DIAGONAL (the default) every scale given to the filter is a fraction of the input's
 * bounding-box diagonal; with ABSOLUTE it is a length in the input's units. The absolute scales actually used are
 * always written to the output's field data array `GLSScales`.
 *
 * Inputs: a vtkPolyData (only its points are used) with oriented normals: the array selected with
 * SetInputArrayToProcess(0, ...), by default the active point normals (run vtkGLSNormalEstimation first if there are
 * none). Normals need not be unit (they are normalized); points with non-finite coordinates or with zero or
 * non-finite normals are left out of every neighbourhood; points with non-finite coordinates get NaN results.
 *
 * Bad parameters (MinScale <= 0, MinScale > MaxScale, NumberOfScales < 1, a non-increasing explicit list), missing
 * or mis-sized normals and empty input give a vtkErrorMacro and RequestData returns 0. The filters report progress
 * and stop early when aborted (the output then carries the input only, no partial arrays).
 *
 * Distributed runs (pvbatch / pvserver on N MPI ranks): when the Controller has more than one process, each rank
 * holds a piece of the cloud. The filters that support it (SupportsDistributedInput: vtkGLSScaleSpace,
 * vtkGLSGeometricVariation, vtkGLSContinuousFeatures, vtkGLSMultiScaleDissimilarity, vtkGLSScaleProfiles,
 * vtkGLSAdaptiveBandwidth, vtkGLSProjection) fetch the other ranks' points
 * within the largest scale of their piece's bounding box (ghosts, see vtkGLSDistributedCloud), fit their own points
 * only, and write arrays for their own points only; the bounding-box diagonal (for relative scales) and the
 * automatic MinimumNeighbors are reduced over all ranks, so the results equal a serial run's (to the summation order
 * of the neighbours, about 1e-15 relative). A rank may hold no points. The output's field data then also carries
 * GLSGhostPoints (how many ghost points this rank used). The other filters are serial-only: on more than one
 * process they stop with an error (a piece alone would give wrong values near its boundary).
 */
#ifndef vtkGLSScaleFilterBase_h
#define vtkGLSScaleFilterBase_h

#include "vtkGLSFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

class vtkDataArray;
class vtkFieldData;
class vtkGLSDistributedCloud;
class vtkMultiProcessController;
class vtkPolyData;

namespace gls
{
class ScaleSampleSink;
class ScaleSpaceEngine;
struct ParallelOptions;
}

class VTKGLSFILTERS_EXPORT vtkGLSScaleFilterBase : public vtkPolyDataAlgorithm
{
public:
  vtkTypeMacro(vtkGLSScaleFilterBase, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ScaleUnitsType
  {
    ABSOLUTE = 0,            ///< scales are lengths in the input's units
    RELATIVE_TO_DIAGONAL = 1 ///< scales are fractions of the input bounding-box diagonal
  };
  enum ScaleSamplingType
  {
    LINEAR = 0,     ///< t_k = min + (max - min) k / (S - 1)
    QUADRATIC = 1,  ///< t_k = min + (max - min) (k / (S - 1))^2, the paper's sampling
    LOGARITHMIC = 2 ///< t_k = min (max / min)^(k / (S - 1))
  };

  ///@{
  /// How MinScale, MaxScale, the explicit scales and (for the dissimilarity) the prior range are read.
  /// Default RELATIVE_TO_DIAGONAL.
  vtkSetClampMacro(ScaleUnits, int, ABSOLUTE, RELATIVE_TO_DIAGONAL);
  vtkGetMacro(ScaleUnits, int);
  void SetScaleUnitsToAbsolute() { this->SetScaleUnits(ABSOLUTE); }
  void SetScaleUnitsToRelativeToDiagonal() { this->SetScaleUnits(RELATIVE_TO_DIAGONAL); }
  ///@}

  ///@{
  /// Smallest and largest scale (see ScaleUnits). Defaults 0.008 and 0.08 (0.8% and 8% of the diagonal).
  vtkSetMacro(MinScale, double);
  vtkGetMacro(MinScale, double);
  vtkSetMacro(MaxScale, double);
  vtkGetMacro(MaxScale, double);
  ///@}

  ///@{
  /// Number of sampled scales (default 20). With 1, the single scale is MinScale.
  vtkSetMacro(NumberOfScales, int);
  vtkGetMacro(NumberOfScales, int);
  ///@}

  ///@{
  /// Spacing of the sampled scales (default QUADRATIC).
  vtkSetClampMacro(ScaleSampling, int, LINEAR, LOGARITHMIC);
  vtkGetMacro(ScaleSampling, int);
  void SetScaleSamplingToLinear() { this->SetScaleSampling(LINEAR); }
  void SetScaleSamplingToQuadratic() { this->SetScaleSampling(QUADRATIC); }
  void SetScaleSamplingToLogarithmic() { this->SetScaleSampling(LOGARITHMIC); }
  ///@}

  ///@{
  /// An explicit list of scales (see ScaleUnits), used instead of Min/Max/Number/Sampling when not empty. Must be
  /// strictly increasing.
  void AddScale(double scale);
  void RemoveAllScales();
  int GetNumberOfExplicitScales() const { return static_cast<int>(this->ExplicitScales.size()); }
  double GetExplicitScale(int i) const { return this->ExplicitScales.at(static_cast<std::size_t>(i)); }
  ///@}

  ///@{
  /// Fits with fewer neighbours strictly inside the ball are NaN. 0 (default) = automatic: 6 for 3D input, 3 for a
  /// 2D curve (all points in the plane z = const with normals in that plane).
  vtkSetClampMacro(MinimumNeighbors, int, 0, VTK_INT_MAX);
  vtkGetMacro(MinimumNeighbors, int);
  ///@}

  ///@{
  /// Weights of the three terms of the geometric variation nu (dimensionless, default 1). Used by the filters that
  /// compute nu (vtkGLSGeometricVariation, vtkGLSContinuousFeatures); ignored by the others.
  vtkSetClampMacro(WTau, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(WTau, double);
  vtkSetClampMacro(WEta, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(WEta, double);
  vtkSetClampMacro(WKappa, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(WKappa, double);
  ///@}

  ///@{
  /// When on (default), a filter that finds the per-scale arrays of an upstream vtkGLSScaleSpace (and its
  /// GLSScales field data) uses them and their scales instead of refitting; this filter's own scale parameters are
  /// then ignored. Turn off to always refit at this filter's scales.
  vtkSetMacro(ReuseInputScaleSpace, bool);
  vtkGetMacro(ReuseInputScaleSpace, bool);
  vtkBooleanMacro(ReuseInputScaleSpace, bool);
  ///@}

  enum BackendType
  {
    BACKEND_AUTO = 0, ///< CUDA when this build has it and a working device is present, else the CPU
    BACKEND_CPU = 1,  ///< the multi-threaded CPU engine
    BACKEND_CUDA = 2  ///< the CUDA engine; without a usable device: one warning naming the reason, then the CPU
  };

  ///@{
  /// Where the fits run (default BACKEND_AUTO). Both backends run the same per-point code in double precision and
  /// agree to about 1e-12 relative. The backend that actually ran is written to the output's field data array
  /// GLSBackend ("CPU" or "CUDA").
  vtkSetClampMacro(Backend, int, BACKEND_AUTO, BACKEND_CUDA);
  vtkGetMacro(Backend, int);
  void SetBackendToAuto() { this->SetBackend(BACKEND_AUTO); }
  void SetBackendToCPU() { this->SetBackend(BACKEND_CPU); }
  void SetBackendToCUDA() { this->SetBackend(BACKEND_CUDA); }
  ///@}

  ///@{
  /// Memory this filter may allocate for its outputs and scratch, in MiB (0, the default: half of the physical
  /// memory). Before allocating, the filter estimates what it needs; above the budget it stops with an error that
  /// says how much it needs and what to change (fewer scales, OutputPrecision FLOAT, skipping arrays, or the fused
  /// filters that store nothing per scale).
  vtkSetClampMacro(MemoryBudget, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MemoryBudget, double);
  ///@}

  /// The backend the last fit of this filter ran on ("CPU", "CUDA"), or "" if it reused stored arrays.
  const char* GetLastBackendUsed() const { return this->LastBackendUsed.c_str(); }

  ///@{
  /// Worker threads (0 = all hardware threads, the default). Results are bitwise identical for any value.
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /// The controller of a distributed run (default: the global controller when the filter is created, as ParaView's
  /// pvbatch and pvserver set it). Null or a single process: serial. See the class documentation.
  virtual void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  /// The absolute scales this filter would use for the given input, or an empty vector (and an error) when the
  /// parameters are invalid. In a distributed run (inside RequestData) relative scales use the diagonal of all the
  /// pieces.
  std::vector<double> ComputeAbsoluteScales(vtkPolyData* input);

  /// The point array an algorithm selected with SetInputArrayToProcess(index, ...): the named array, or the active
  /// normals when no name (or an empty one, as ParaView sets before it knows the input's arrays) is selected.
  static vtkDataArray* FindSelectedNormals(vtkAlgorithm* self, int index, vtkPolyData* input);

  /// The array name an algorithm selected with SetInputArrayToProcess(index, ...), or null when none (or an empty
  /// name, as ParaView sets before it knows the input's arrays) is selected.
  static const char* SelectedArrayName(vtkAlgorithm* self, int index);

protected:
  vtkGLSScaleFilterBase();
  ~vtkGLSScaleFilterBase() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  /// Bounding-box diagonal of the points with finite coordinates (0 when none or all coincide).
  static double FiniteDiagonal(vtkPolyData* input);

  /// Converts a length given in ScaleUnits into an absolute length for this input (the whole distributed input
  /// in a distributed run).
  double ToAbsoluteLength(vtkPolyData* input, double value) const;

  /// FiniteDiagonal of the input, or of all the pieces in a distributed run.
  double InputDiagonal(vtkPolyData* input) const;

  /// Whether this filter computes correct results on a distributed input (a piece per process, see the class
  /// documentation). False by default: such a filter stops with an error when its Controller has several processes.
  virtual bool SupportsDistributedInput() const { return false; }

  /// The collective steps of the current run (serial identities in a serial run); valid after PrepareOutput or
  /// PrepareScaleSamples.
  const vtkGLSDistributedCloud& Distributed() const { return *this->DistributedRun; }

  /// Starts a run: in a distributed run, checks that this filter supports it (else an error) and reduces the
  /// pieces' bounds; an empty piece is fine as long as some rank has points. Called by PrepareOutput and
  /// PrepareScaleSamples (once per run). False with an error otherwise, on every rank alike.
  bool BeginRun(vtkPolyData* input);

  /// Copies the points and the selected normals into double buffers; false (with an error) when the input is empty
  /// or the normals are missing or mis-sized.
  bool GatherPointsAndNormals(vtkPolyData* input, std::vector<double>& points, std::vector<double>& normals);

  /// The normals selected with SetInputArrayToProcess(0, ...): the named point array, or the active normals when
  /// no name (or an empty one) is selected. Null when absent.
  vtkDataArray* FindSelectedNormals(vtkPolyData* input);

  /// MinimumNeighbors, resolved for this input (see MinimumNeighbors).
  double ResolveMinimumNeighbors(const std::vector<double>& points, const std::vector<double>& normals) const;

  /// What a filter will store per point and scale, for the memory budget, and what to say when it is too much.
  struct OutputCost
  {
    double BytesPerPointScale = 0.0; ///< output bytes for each (point, scale) pair
    const char* What = "the fused GLS fit";
    const char* Advice = "Use fewer points or scales.";
  };

  /// Chooses where the samples of RunScaleSamples come from: the arrays a vtkGLSScaleSpace upstream stored (when
  /// ReuseInputScaleSpace is on, AcceptsStoredScaleSpace() and GLSScales plus every array named by needDescriptors --
  /// GLSTau, GLSKappa, GLSFitness -- and needDerivatives -- GLSdTau, GLSdKappa, GLSdEta -- are present), else a fit
  /// of points and normals at this filter's scales. `scales` receives the absolute scales. Checks the memory budget
  /// (the filter's outputs per `cost`, plus the engine when it fits) before allocating. False (with an error) on bad
  /// input or a budget exceeded.
  bool PrepareScaleSamples(vtkPolyData* input, bool needDescriptors, bool needDerivatives,
    std::vector<double>& scales, const OutputCost& cost);
  bool PrepareScaleSamples(
    vtkPolyData* input, bool needDescriptors, bool needDerivatives, std::vector<double>& scales)
  {
    return this->PrepareScaleSamples(input, needDescriptors, needDerivatives, scales, OutputCost());
  }

  /// Feeds the sink with the samples of the given points (all when ids is null), on all threads, reporting progress
  /// from progressBegin to progressEnd. Returns false if aborted. Call PrepareScaleSamples first.
  bool RunScaleSamples(gls::ScaleSampleSink& sink, const std::vector<std::uint64_t>* ids = nullptr,
    double progressBegin = 0.0, double progressEnd = 1.0);

  /// Maps a point's nu at the given scales (one value per scale) to one value; called concurrently, read-only.
  using VariationReducer = std::function<double(const double* nu, const std::vector<double>& scales)>;

  /// Reduces every point's geometric variation over the scales to one value (the filters that summarize nu per
  /// point: continuous features, adaptive bandwidth). nu comes from an upstream GLSGeometricVariation array and its
  /// GLSScales when ReuseInputScaleSpace allows and they match the input, else from a fused fit at this filter's
  /// scales with WTau/WEta/WKappa that stores nothing per scale. `scales` receives the scales used; progress runs
  /// from 0 to progressEnd. False (with an error) on bad input; `aborted` tells whether the run was cut short
  /// (then `out` is incomplete).
  bool ReduceVariationPerPoint(vtkPolyData* input, const VariationReducer& reduce, std::vector<double>& scales,
    double* out, double progressEnd, bool& aborted);

  /// Whether this filter may use an upstream scale space at all (vtkGLSScaleProfiles samples its own scales).
  virtual bool AcceptsStoredScaleSpace() const { return true; }

  /// Output = input (shallow) with its own field data, ready for new arrays; forgets the last backend used.
  /// False (with an error) when the input has no points.
  bool PrepareOutput(vtkPolyData* input, vtkPolyData* output);

  /// Runs the engine on this filter's Backend, records the backend used (and warns once per filter when a CUDA
  /// request falls back to the CPU). Returns false if aborted.
  bool RunEngine(const gls::ScaleSpaceEngine& engine, gls::ScaleSampleSink& sink,
    const std::vector<std::uint64_t>* ids, const gls::ParallelOptions& parallel);

  /// False (with an error naming `needed` and `advice`) when `needed` bytes exceed the MemoryBudget.
  bool CheckMemoryBudget(double needed, const char* what, const char* advice);

  /// Bytes of the engine's own buffers for n points and S scales (coordinates, normals, grid, per-thread scratch).
  double EngineBytes(vtkIdType n, std::size_t S) const;

  /// Writes the backend of the last fit as the field-data string array GLSBackend (nothing if none ran) and, in a
  /// distributed run, the number of ghost points this rank used as GLSGhostPoints.
  void StoreBackend(vtkFieldData* fd) const;

  /// Writes `scales` as the field-data array GLSScales.
  static void StoreScales(vtkFieldData* fd, const std::vector<double>& scales);

  /// Reads GLSScales from the field data; empty if absent or invalid.
  static std::vector<double> ReadStoredScales(vtkFieldData* fd);

  /// Names the components "t=<scale>" (several components per scale get "t=<scale> x|y|z").
  static void NameScaleComponents(vtkDataArray* array, const std::vector<double>& scales, int perScale);

  /// Progress and abort glue for the core: maps [0, 1] to [begin, end] of this filter's progress.
  bool ReportProgress(double fraction, double begin, double end);

  int ScaleUnits;
  double MinScale;
  double MaxScale;
  int NumberOfScales;
  int ScaleSampling;
  std::vector<double> ExplicitScales;
  int MinimumNeighbors;
  double WTau;
  double WEta;
  double WKappa;
  bool ReuseInputScaleSpace;
  int Backend;
  double MemoryBudget;
  int NumberOfThreads;
  std::string LastBackendUsed;
  bool WarnedAboutBackend = false;
  vtkMultiProcessController* Controller = nullptr;
  std::unique_ptr<vtkGLSDistributedCloud> DistributedRun;
  double DistributedDiagonal = 0.0;
  long long GhostPointsUsed = -1; ///< ghosts of the last distributed fit (-1: none ran)

private:
  struct Internals;
  std::unique_ptr<Internals> Source;

  vtkGLSScaleFilterBase(const vtkGLSScaleFilterBase&) = delete;
  void operator=(const vtkGLSScaleFilterBase&) = delete;
};

#endif
