// Where a scale filter's samples come from (private to the module): a fit of the run's cloud by the core's engine,
// or the per-scale arrays an upstream vtkGLSScaleSpace stored (read back through the descriptor table), so that
// downstream filters reuse them instead of refitting. Either way the filter's sink receives one gls::ScaleSample
// per scale for each point it asks for.
#ifndef vtkGLSSampleSource_h
#define vtkGLSSampleSource_h

#include "vtkType.h" // vtkIdType

#include "gls/Backend.h"
#include "gls/ScaleSpaceEngine.h"
#include "gls/TiledScaleSpace.h"

#include <cstdint>
#include <memory>
#include <vector>

class vtkDataArray;
class vtkDataSet;
struct vtkGLSCloud;

class vtkGLSSampleSource
{
public:
  /// A fit of the cloud's points and normals (owned points, then ghosts) at settings.scales. Only the owned points
  /// are evaluated; the ghosts are neighbours only. An empty piece has nothing to fit. When the cloud merged
  /// coincident points, each distinct position is evaluated once and its samples go to every copy; the sink sees
  /// the input's point ids either way. tiles > 1: the cloud is evaluated one spatial tile at a time (with the same
  /// samples: gls::TiledScaleSpace), at most that many. The cloud must outlive the source.
  static std::unique_ptr<vtkGLSSampleSource> Fit(
    const vtkGLSCloud& cloud, gls::ScaleSpaceSettings settings, std::size_t tiles = 1);

  /// Fit with one engine over the whole cloud, which frees the cloud's coordinates (vtkGLSCloud::ReleaseCoordinates)
  /// as soon as the engine holds its sorted copies of them, before it builds its cells: the two copies are held
  /// together only while one is made.
  static std::unique_ptr<vtkGLSSampleSource> FitWholeReleasing(vtkGLSCloud& cloud, gls::ScaleSpaceSettings settings);

  /// A fit that Feed will ask for the points `only` only (this piece's input ids, at most
  /// gls::TiledScaleSpace::kMaxSelected of them): built over their neighbourhoods instead of the whole cloud, with
  /// the same samples.
  static std::unique_ptr<vtkGLSSampleSource> FitAround(
    const vtkGLSCloud& cloud, gls::ScaleSpaceSettings settings, const std::vector<std::uint64_t>& only);

  /// The arrays a vtkGLSScaleSpace stored for `scaleCount` scales: the descriptors (GLSTau, GLSKappa, GLSFitness)
  /// and/or the derivatives (GLSdTau, GLSdEta, GLSdKappa) and/or the principal curvatures (GLSK1, GLSK2,
  /// GLSPrincipalDirection1 and 2: fed to consumeCurvatures), as asked. Null when any asked array is missing or has
  /// the wrong shape.
  static std::unique_ptr<vtkGLSSampleSource> Stored(
    vtkDataSet* input, std::size_t scaleCount, bool descriptors, bool derivatives, bool curvatures = false);

  /// Nothing to feed: an empty piece of a distributed input that goes along with the others.
  static std::unique_ptr<vtkGLSSampleSource> Empty();

  /// True when Feed runs the core's fits on this piece (false for stored arrays and empty pieces).
  bool RunsFits() const { return this->Engine != nullptr; }

  /// Feeds the sink with the samples of the given points of this piece (all of them when ids is null) on
  /// parallel.threads threads, reporting progress through parallel.progress. A fit runs on the backend of its
  /// settings and says in `report` where it ran. A stored sample is valid when every value read back is finite; the
  /// values not read back are NaN. Returns false if aborted.
  bool Feed(gls::ScaleSampleSink& sink, const std::vector<std::uint64_t>* ids, const gls::ParallelOptions& parallel,
    gls::RunReport& report) const;

  /// The buffers of an engine over the cloud under these settings (gls::ScaleSpaceEngine::footprint, its pyramid
  /// counted from the points), besides the points and normals it is given (vtkGLSCloud::BytesPerPoint each; with
  /// them, bytes(their bytes), when FitWholeReleasing frees them once the engine holds its copies); and of its
  /// threads' scratch: its share of `points` points (ghosts included) when it runs on a tile of that size.
  static gls::EngineFootprint EngineBytes(const vtkGLSCloud& cloud, const gls::ScaleSpaceSettings& settings);
  static double EngineShareBytes(
    double wholeEngineBytes, std::size_t wholePoints, std::size_t points, std::size_t S, int threads);

  /// Tiles of the fit (1 when it is not tiled or is no fit) and points of its largest tile, ghosts included.
  std::size_t TileCount() const { return this->Engine ? this->Engine->tileCount() : 1; }
  std::size_t LargestTile() const { return this->Engine ? this->Engine->largestTile() : this->PointCount; }

private:
  vtkGLSSampleSource() = default;
  /// A source of the cloud's owned points at `scales` scales, without its engine yet.
  static std::unique_ptr<vtkGLSSampleSource> OfCloud(const vtkGLSCloud& cloud, std::size_t scales);
  /// Feed of a fit of merged coincident points: each distinct position once, its samples to the input points it
  /// stands for.
  bool FeedDistinctPositions(gls::ScaleSampleSink& sink, const std::vector<std::uint64_t>* ids,
    const gls::ParallelOptions& parallel, gls::RunReport& report) const;
  /// Feed of the stored arrays: each point's samples (and curvatures, when stored) read back.
  bool FeedStored(
    gls::ScaleSampleSink& sink, const std::vector<std::uint64_t>* ids, const gls::ParallelOptions& parallel) const;
  /// The stored sample of the point `tuple` at scale k: the values read back, NaN for the others; valid when every
  /// value read back is finite.
  gls::ScaleSample StoredSample(vtkIdType tuple, std::size_t k) const;
  /// The stored principal curvatures of the point `tuple` at scale k.
  gls::PrincipalCurvatures StoredCurvature(vtkIdType tuple, std::size_t k) const;

  std::unique_ptr<gls::TiledScaleSpace> Engine; ///< null for an empty piece
  const vtkGLSCloud* Cloud = nullptr;            ///< the fitted cloud (its merge of coincident points)
  std::size_t PointCount = 0;
  std::size_t ScaleCount = 0;
  std::vector<std::pair<int, vtkDataArray*>> StoredArrays; ///< (descriptor id, its array), for the stored samples
  std::vector<std::pair<int, vtkDataArray*>> StoredCurvatures; ///< (curvature array id, its array)
};

#endif
