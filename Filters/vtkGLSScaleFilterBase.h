/**
 * @class   vtkGLSScaleFilterBase
 * @brief   The GLS filters that work over a range of scales: the scales, the backend, and the samples of every
 *          point at every scale (a fit, or the arrays of an upstream vtkGLSScaleSpace).
 *
 * A scale t is the radius of the compact weight (d^2/t^2 - 1)^2 of the GLS fit, a length. The scales are either an
 * explicit list (AddScale) or NumberOfScales values from MinScale to MaxScale with the chosen ScaleSampling, all
 * in ScaleUnits (by default fractions of the input's bounding-box diagonal). The absolute scales used are always
 * written to the output's field data array `GLSScales`, and where the fits ran to `GLSBackend`.
 *
 * The run (RequestData, see vtkGLSFilterBase): CheckParameters (the filter's own checks), the scales, the memory
 * budget, the cloud with its ghosts, then the samples: a filter that consumes a scale space and allows it
 * (ReuseInputScaleSpace) reads the arrays an upstream vtkGLSScaleSpace stored (and its GLSScales) instead of
 * refitting; otherwise the core fits every point at every scale in one pass over its neighbours (docs/math.md).
 * ComputeOutputs, the filter's part, then feeds its sink with the samples and adds its arrays.
 *
 * Bad parameters (MinScale <= 0, MinScale > MaxScale, NumberOfScales < 1, a non-increasing explicit list),
 * missing or mis-sized normals and empty input give a vtkErrorMacro and RequestData returns 0. The filters report
 * progress and stop early when aborted (the output then carries the input only, no partial arrays).
 *
 * Evaluation: each ball's moments are summed over every point of the ball (EXACT), or over a multi-resolution
 * pyramid whose cells of edge at most Accuracy times their distance from the evaluated point are taken whole
 * (MULTIRESOLUTION: cost per point about constant whatever the density; exact on spheres and planes; see
 * docs/math.md, "Multi-resolution evaluation", for the error). AUTO (the default) is exact while the largest ball
 * holds on average at most about 5,000 points. The output's field data GLSEvaluation says which ran ("Exact" or
 * "Multiresolution"), and GLSAccuracy the epsilon of a multi-resolution run.
 *
 * Distributed runs: the ghosts are the other ranks' points within the largest scale of each piece's bounding box
 * (enlarged by the largest cell a multi-resolution run may take whole), so the results equal a serial run's (to
 * the summation order of the neighbours, about 1e-15 relative). The output's field data then also carries
 * GLSGhostPoints. See docs/distributed.md.
 */
#ifndef vtkGLSScaleFilterBase_h
#define vtkGLSScaleFilterBase_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSFitFilterBase.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

class vtkDataArray;
class vtkFieldData;
class vtkGLSSampleSource;

namespace gls
{
class ScaleSampleSink;
struct ScaleSpaceSettings;
struct MultiresolutionSettings;
}

class VTKGLSFILTERS_EXPORT vtkGLSScaleFilterBase : public vtkGLSFitFilterBase
{
public:
  vtkTypeMacro(vtkGLSScaleFilterBase, vtkGLSFitFilterBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ScaleSamplingType
  {
    LINEAR = 0,     ///< t_k = min + (max - min) k / (S - 1)
    QUADRATIC = 1,  ///< t_k = min + (max - min) (k / (S - 1))^2, the paper's sampling
    LOGARITHMIC = 2 ///< t_k = min (max / min)^(k / (S - 1))
  };

  ///@{
  /// Smallest and largest scale (in ScaleUnits). Defaults 0.008 and 0.08 (0.8% and 8% of the diagonal).
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
  vtkSetMacro(ScaleSampling, int);
  vtkGetMacro(ScaleSampling, int);
  void SetScaleSamplingToLinear() { this->SetScaleSampling(LINEAR); }
  void SetScaleSamplingToQuadratic() { this->SetScaleSampling(QUADRATIC); }
  void SetScaleSamplingToLogarithmic() { this->SetScaleSampling(LOGARITHMIC); }
  ///@}

  ///@{
  /// An explicit list of scales (in ScaleUnits), used instead of Min/Max/Number/Sampling when not empty. Must be
  /// strictly increasing.
  void AddScale(double scale);
  void RemoveAllScales();
  int GetNumberOfExplicitScales() const { return static_cast<int>(this->ExplicitScales.size()); }
  double GetExplicitScale(int i) const { return this->ExplicitScales.at(static_cast<std::size_t>(i)); }
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
  vtkSetMacro(Backend, int);
  vtkGetMacro(Backend, int);
  void SetBackendToAuto() { this->SetBackend(BACKEND_AUTO); }
  void SetBackendToCPU() { this->SetBackend(BACKEND_CPU); }
  void SetBackendToCUDA() { this->SetBackend(BACKEND_CUDA); }
  ///@}

  enum EvaluationType
  {
    EVALUATION_AUTO = 0,           ///< exact while the largest ball averages at most about 5,000 points, else cells
    EVALUATION_EXACT = 1,          ///< every point of every ball (the one pass)
    EVALUATION_MULTIRESOLUTION = 2 ///< cells of edge <= Accuracy * distance taken whole
  };

  ///@{
  /// How the moments of each ball are evaluated (default EVALUATION_AUTO); see the class documentation.
  vtkSetMacro(Evaluation, int);
  vtkGetMacro(Evaluation, int);
  void SetEvaluationToAuto() { this->SetEvaluation(EVALUATION_AUTO); }
  void SetEvaluationToExact() { this->SetEvaluation(EVALUATION_EXACT); }
  void SetEvaluationToMultiresolution() { this->SetEvaluation(EVALUATION_MULTIRESOLUTION); }
  ///@}

  ///@{
  /// Epsilon of the multi-resolution evaluation (dimensionless, default 0.5): a cell is taken whole, its points
  /// weighted from its sums up to the second order (docs/math.md), where its edge is at most Accuracy times its
  /// distance from the evaluated point. Smaller is closer to exact and slower (the samples per point grow as
  /// 1 / Accuracy^2).
  vtkSetMacro(Accuracy, double);
  vtkGetMacro(Accuracy, double);
  ///@}

  /// How the last fit of this filter evaluated the moments ("Exact", "Multiresolution"), or "" if none ran.
  const char* GetLastEvaluationUsed() const { return this->LastEvaluationUsed.c_str(); }

  /// The backend the last fit of this filter ran on ("CPU", "CUDA"), or "" if it reused stored arrays.
  const char* GetLastBackendUsed() const { return this->LastBackendUsed.c_str(); }

  /// The spatial tiles the last fit was cut into to meet MemoryBudget (1: not cut; 0: no fit was prepared, e.g.
  /// refused or reusing stored arrays). Known as soon as the fit starts (an observer of the first progress event
  /// can read it).
  int GetLastTileCount() const { return this->LastTileCount; }

  /// The absolute scales this filter would fit for the given (serial) input, or an empty vector (and an error) when
  /// the parameters are invalid.
  std::vector<double> ComputeAbsoluteScales(vtkPointSet* input);

protected:
  void DescribeSettings(std::vector<SettingRange>& settings) override;

  vtkGLSScaleFilterBase();
  ~vtkGLSScaleFilterBase() override;

  /// What a filter needs of the samples, and what its outputs cost in memory.
  struct SampleRequest
  {
    bool Descriptors = false;   ///< tau, kappa and phi must be read back from stored arrays
    bool Derivatives = false;   ///< dtau, deta and dkappa must be read back from stored arrays
    bool VariationWillDo = false; ///< an upstream GLSGeometricVariation (nu) at its GLSScales is enough
    bool MayReuseInput = false; ///< stored arrays may replace a fit (the filter's ReuseInputScaleSpace)
    /// The fit also computes the principal curvatures (gls::ScaleSpaceSettings::principalCurvatures), fed to the
    /// sink's consumeCurvatures (read back from the stored arrays when they replace a fit).
    bool PrincipalCurvatures = false;
    double BytesPerPointScale = 0.0; ///< output bytes for each (point, scale) pair
    double BytesPerPoint = 0.0;      ///< output bytes for each point, whatever the number of scales
    double BytesPerScale = 0.0;      ///< working bytes for each scale, whatever the number of points
    /// The only points the filter feeds (this piece's input ids), when it feeds few (a profile's): the fit is then
    /// built around them (vtkGLSSampleSource::FitAround) whatever the cloud's size. Null: every point.
    const std::vector<std::uint64_t>* Only = nullptr;
    const char* What = "the fused GLS fit";
    const char* Advice = "Use fewer points or scales.";
  };

  /// The run of a scale filter (final): CheckParameters, PrepareSamples, ComputeOutputs, and the field data.
  int Execute(vtkGLSRun& run) override;

  /// The filter's own checks and per-run state, before the scales and samples are prepared. Default: none.
  virtual bool CheckParameters(vtkGLSRun& run);

  /// What the filter needs of the samples (called after CheckParameters).
  virtual SampleRequest GetSampleRequest(const vtkGLSRun& run) const = 0;

  /// The most spatial tiles a fit is cut into to meet the MemoryBudget.
  static constexpr std::size_t kMaximumTiles = 4096;
  /// Doubling the tiles goes on while the largest tile shrinks below this fraction of its size (beyond, the ghost
  /// bands of the largest scale hold most of each tile, and more tiles cost time without saving memory).
  static constexpr double kTileShrink = 0.9;

  /// Whether the fit of run.Cloud is cut into spatial tiles: not (`tiled` left null) when the engine fits in the
  /// MemoryBudget (its build, then the engine beside `fixed` bytes of outputs), with compact normals if that is what
  /// fits (settings.multiresolution.compactNormals and run.CompactNormals set), else the fewest tiles (doubling) whose
  /// largest fits, planned in `tiled`. False (with an error naming the budget) when none does.
  bool ChooseTiles(vtkGLSRun& run, gls::ScaleSpaceSettings& settings, double fixed, const SampleRequest& request,
    std::unique_ptr<vtkGLSSampleSource>& tiled);

  /// Sets run.Scales for a fit: by default the scale list at the run's diagonal. False (with an error) on invalid
  /// scale parameters.
  virtual bool ResolveScales(vtkGLSRun& run);

  /// Completes run.Cloud, the points and normals to fit (this piece's; the ghosts are added after). Default: the
  /// input's points and selected normals.
  virtual bool GatherFitCloud(vtkGLSRun& run);

  /// The filter's part: feeds its sink (FeedSamples) and adds its arrays to its outputs. Returns an Outcome.
  virtual int ComputeOutputs(vtkGLSRun& run) = 0;

  /// Feeds the sink with the run's samples of the given points (all of this piece's when ids is null), on all
  /// threads, reporting progress from progressBegin to progressEnd, and records the backend of a fit (warning once
  /// per filter when a CUDA request falls back to the CPU). Returns false if aborted.
  bool FeedSamples(vtkGLSRun& run, gls::ScaleSampleSink& sink, const std::vector<std::uint64_t>* ids = nullptr,
    double progressBegin = 0.0, double progressEnd = 1.0);

  /// The scale list of the parameters for a diagonal (relative units) and a sampling; empty with an error when
  /// the parameters are invalid.
  std::vector<double> ScaleList(double diagonal, int sampling);

  /// Writes `scales` as the field-data array GLSScales.
  static void WriteScales(vtkFieldData* fd, const std::vector<double>& scales);

  /// Names the components "t=<scale>" (several components per scale get "t=<scale> x|y|z").
  static void NameScaleComponents(vtkDataArray* array, const std::vector<double>& scales, int perScale);

  double MinScale;
  double MaxScale;
  int NumberOfScales;
  int ScaleSampling;
  std::vector<double> ExplicitScales;
  int Backend;
  int Evaluation;
  double Accuracy;
  std::string LastBackendUsed;
  std::string LastEvaluationUsed;
  int LastTileCount = 0;
  bool WarnedAboutBackend = false;

private:
  /// The samples of the run: stored arrays when the request allows and they are there, else a fit of the cloud
  /// (scales, memory budget, cloud, ghosts, engine). Collective; false (with an error) on failure.
  bool PrepareSamples(vtkGLSRun& run, const SampleRequest& request);
  /// The stored arrays' samples, when every piece has them: whether they were taken (then `ok` says whether the
  /// memory budget holds their outputs). Collective.
  bool TakeStoredSamples(vtkGLSRun& run, const SampleRequest& request, bool& ok);
  /// A fit of the cloud: scales, the memory budget, the cloud, ghosts, evaluation, tiles, engine. Collective.
  bool PrepareFit(vtkGLSRun& run, const SampleRequest& request);
  /// The bytes a run's large allocations take: `bytes` (per point and scale), plus its per-point and per-scale ones.
  static double RunBytes(const vtkGLSRun& run, const SampleRequest& request, double bytes, double scales);

  /// The largest ghost reach the fit may need (gls::ghostReach): the largest scale, or for a multi-resolution
  /// evaluation (Auto included) the farthest point of a cell a walk may take whole. Collective.
  double GhostReach(const vtkGLSRun& run) const;

  /// The multi-resolution layout's frame (box, spacing, Accuracy) from the whole input: a distributed piece lays out
  /// its pyramid as the serial run does. Collective.
  void LayOutPyramid(const vtkGLSRun& run, gls::MultiresolutionSettings& m) const;

  /// Resolves Evaluation for the run's cloud (Auto: the ball-count estimate, summed over the pieces) and sets the
  /// engine's evaluation settings and run.EvaluationUsed. Collective.
  void ChooseEvaluation(vtkGLSRun& run, gls::ScaleSpaceSettings& settings);

  /// After a fit of every point: one warning (on rank 0) when most fits are NaN at some scales, with the median
  /// neighbour count there. `diagnosis` is the coverage the feed gathered (null for stored samples). Collective.
  void WarnAboutUndefinedScales(const vtkGLSRun& run, const gls::ScaleSampleSink* diagnosis);

  /// Reads GLSScales from the field data; empty if absent or invalid.
  static std::vector<double> ReadStoredScales(vtkFieldData* fd);

  vtkGLSScaleFilterBase(const vtkGLSScaleFilterBase&) = delete;
  void operator=(const vtkGLSScaleFilterBase&) = delete;
};

#endif
