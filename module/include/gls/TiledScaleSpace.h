// TiledScaleSpace evaluates a cloud with ScaleSpaceEngine either whole or one spatial tile at a time (SpatialTiles):
// each tile's engine holds the tile's points and the points within reach of it (its ghost band) and evaluates only
// the tile's own points, so the engine's memory is that of the largest tile with its band rather than the cloud's.
// Every tile lays its grid or pyramid on the whole cloud's lattice and lists its points in the cloud's order, so
// each point gets the samples of the untiled run, bit for bit (the ghost band covers every neighbour and every cell
// a fit takes whole: ghostReach).
#pragma once

#include "gls/ScaleSpaceEngine.h"
#include "gls/SpatialTiles.h"
#include "gls/UninitializedArray.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace gls
{

/// How far from a point the points that can change its samples lie (length unit): the largest scale for the exact
/// evaluation (its ball); for the multi-resolution one (settings.multiresolution with its box and spacing, as
/// resolvePyramidFrame leaves them), the farthest point of a cell a walk takes whole, t (1 + sqrt(3) Accuracy),
/// plus the diagonal of the region the walk is shared by. A spatial tile's band, and a distributed piece's.
double ghostReach(const ScaleSpaceSettings& settings);

class TiledScaleSpace
{
public:
  /// Bytes a tile needs per point (ghosts included) besides its engine's: its list of cloud indices, its copy of the
  /// positions and normals while its engine is built, and a flag.
  static constexpr double kBytesPerTilePoint = 8.0 + 6.0 * 8.0 + 1.0;

  /// points, normals: count interleaved triples. Only the first `evaluated` points are evaluated; the rest (a
  /// distributed piece's ghosts) are neighbours only. tiles <= 1: one engine over the whole cloud, built here on
  /// settings.parallel (its progress and abort, as ScaleSpaceEngine), which calls `inputsCopied` (when given) once it
  /// has read the points and normals for the last time. More: at most that many tiles (fewer where the points cannot
  /// be cut), whose engines are built one after the other inside run(); the points and normals must then outlive this
  /// object (and `inputsCopied` is not called).
  TiledScaleSpace(const double* points, const double* normals, std::size_t count, std::size_t evaluated,
    ScaleSpaceSettings settings, std::size_t tiles, const std::function<void()>& inputsCopied = nullptr);
  /// The most points the filters hand the constructor below: it tests every point of the cloud against each of them.
  static constexpr std::size_t kMaxSelected = 64;
  /// Only the `selected` points (cloud indices below `evaluated`; a few, see kMaxSelected) will be evaluated, as a
  /// scale profile's: one engine over them and the points within reach of them (ghostReach), laid on the
  /// whole cloud's lattice like a tile's and built inside run(), so that their samples are the whole run's, bit for
  /// bit, for the cost of their neighbourhoods instead of the cloud's. The points and normals must outlive this
  /// object.
  TiledScaleSpace(const double* points, const double* normals, std::size_t count, std::size_t evaluated,
    ScaleSpaceSettings settings, const std::vector<std::uint64_t>& selected);

  std::size_t tileCount() const { return this->Whole || this->AroundSelected ? 1 : this->Tiles.count(); }
  /// Points (own and ghosts) of the largest tile; the point count for one tile.
  std::size_t largestTile() const { return this->Largest; }
  /// True when the whole cloud's engine was stopped while it was built (run() then returns false).
  bool buildAborted() const { return this->Whole && this->Whole->buildAborted(); }

  /// ScaleSpaceEngine::run over the evaluated points (all when ids is null; ids are cloud indices below
  /// `evaluated`, and among the selected points when some were): each tile's engine built, run and freed in turn,
  /// progress over all tiles through parallel.progress, each engine with the settings' evaluator (backend
  /// included). The sink sees cloud indices. Returns false if aborted.
  bool run(ScaleSampleSink& sink, const std::vector<std::uint64_t>* ids, const ParallelOptions& parallel,
    RunReport& report) const;

private:
  /// The members both public constructors set.
  TiledScaleSpace(
    const double* points, const double* normals, std::size_t count, std::size_t evaluated, ScaleSpaceSettings settings);
  /// What a part of the cloud's engine takes from the whole cloud: which points may be neighbours, the lattice of
  /// its grid or the frame of its pyramid, and the reach of a point's neighbourhood.
  void layOnTheWholeCloud();
  bool runTile(std::size_t k, ScaleSampleSink& sink, const std::vector<std::uint64_t>* ids,
    const ParallelOptions& parallel, RunReport& report) const;
  /// One engine over `members` (cloud indices, increasing) run on the requested points (cloud indices among the
  /// members; those with own[j], in the engine's order, when null). `first`: its backend report replaces `report`
  /// (a later part's only when it fell back).
  bool runMembers(const std::vector<std::uint64_t>& members, const std::vector<unsigned char>& own,
    const std::vector<std::uint64_t>* requested, ScaleSampleSink& sink, const ParallelOptions& parallel,
    RunReport& report, bool first) const;
  /// The one membership rule of the tiles: 1 when cloud point i is evaluated in tile k (an evaluated point in its
  /// box), 2 when it is only a neighbour there (an admitted point within the ghost reach of the box), 0 otherwise.
  int membership(std::size_t k, std::size_t i) const;
  /// The points (own and ghosts) of every tile (membership, over each point's own box and the boxes near it).
  std::vector<std::size_t> tileSizes() const;
  /// Cloud indices of tile k's points and ghosts, increasing; own[j] says whether members[j] is evaluated here.
  void members(std::size_t k, std::vector<std::uint64_t>& members, std::vector<unsigned char>& own) const;
  /// The points `kind` (0: left out, 1: evaluated, 2: neighbour only) takes, in the cloud's order, as members().
  template <class Kind>
  void collect(const Kind& kind, std::vector<std::uint64_t>& members, std::vector<unsigned char>& own) const;

  const double* Points = nullptr;
  const double* Normals = nullptr;
  std::size_t Count = 0;
  std::size_t Evaluated = 0;
  ScaleSpaceSettings Settings;
  std::unique_ptr<ScaleSpaceEngine> Whole;    ///< one tile: the engine over the whole cloud
  std::vector<std::uint64_t> WholeOwnedOrder; ///< one tile with points not evaluated: the engine's order without them
  SpatialTiles Tiles;
  UninitializedArray<unsigned char> Admit;    ///< tiles: which points may be neighbours (admitOrientedPoints)
  double Reach = 0.0;
  std::size_t Largest = 0;
  bool AroundSelected = false;                ///< the selected points' constructor
  std::vector<std::uint64_t> Selected;        ///< its points, increasing
  std::vector<std::uint64_t> SelectedMembers; ///< them and the points within reach of them, increasing
  std::vector<unsigned char> SelectedOwn;     ///< whether each member is selected
};

} // namespace gls
