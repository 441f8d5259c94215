// The CPU form of the multi-resolution evaluation (evaluateAllScalesMultiresolution, MultiresolutionReferenceWalk.h):
// the same cells taken whole and the same points read one by one, found level by level instead of depth first, so that
// each level's cells are classified in a loop without a branch per cell (the depth-first walk mispredicts about one
// branch per cell: measured 20 ns per cell), then binned and added in batches. The walk depends on p's walkRegion only,
// so it runs once for consecutive points of one region, and its samples are packed once with their sums about the
// region's corner (PackedSample); each point adds them as they are and moves the running sum of its bins to itself at
// each scale (exact algebra, a shift of the origin). The sums are therefore the same sums in another order and about
// another origin: results agree with the host/device loop to rounding (the tests bound it) and are deterministic for
// any thread count. The implementation: src/multiresolution/MultiresolutionKernel.cpp, which lists its parts.
#pragma once

#include "gls/MultiresolutionReferenceWalk.h"
#include "gls/OnePassKernel.h"

#include <cstdint>
#include <vector>

namespace gls
{

/// What a walk depends on: the pyramid (its nodes, point count and accuracy), the largest and smallest scales and
/// the walk region.
struct WalkKey
{
  const PyramidNode* nodes = nullptr;
  std::uint64_t count = 0;
  double accuracy = 0.0, radius = 0.0, smallest = 0.0, linearizedDistance = 0.0;
  WalkRegion region{};    ///< p's walk region
  WalkRegion farRegion{}; ///< a far walk's region (FarRule); for the walk region's own walk, the largest one
  const double* squaredScales = nullptr; ///< the shells the linearized cells were binned into
  int scaleCount = 0;
};

/// The linearized cells of a far region F (FarRule), summed once for every point of F, their sums about F's corner:
/// per shell, the terms of movedShare summed over the cells (each cell's share expansion times its F and H, with a
/// = c - r its direction from F's centre r): `value`, `slope`, `slopeA[i]` (times a_i) and `curvatureAA[ij]` (times
/// a_i a_j, i <= j: xx, xy, xz, yy, yz, zz). A point p, u = p - r, adds value + |u|^2 slope - 2 u . slopeA +
/// 2 u^T curvatureAA u: each cell's mean moves by |u|^2 - 2 a . u, and the second-order term is 2 (a . u)^2.
template <typename Set>
struct LinearizedBinsT
{
  std::vector<AggregateMomentsT<Set>> value, slope, slopeA[3], curvatureAA[6];
  std::size_t cells = 0; ///< linearized cells of the far region (0: nothing to add)
  int firstShell = 0;    ///< the lowest shell they reach (the bins below are zeros)
};

/// The samples of a walk that lie inside the smallest scale's sphere for every point of its walk region (the cells
/// whose spread of squared distances stays below scales[0]^2, the points read one by one that stay there: near p, most
/// of them), summed once per region as the exact polynomial of p that their share of the first shell is: each adds F,
/// mean F + 2 H and (mean^2 + V) F + 4 mean H (wholeShare; a point: f, d2 f, d2^2 f) to the three moments, and mean = M
/// - 2 a . u + |u|^2 with u = p - (the region's centre), a = its centroid (or position) - the centre, M = |a|^2 + its
/// spread per point. The sums over the samples of F and H times 1, M, a_i, M a_i, a_i a_j and M^2 + V give those
/// moments for every p of the region (addInnerSums in src/multiresolution/MultiresolutionPacking.h); their sums are
/// about the walk's origin, as the packed samples'.
template <typename Set>
struct InnerSumsT
{
  /// Of F: 1, M, a (3), M^2 + V, M a (3), a a^T (6: xx, xy, xz, yy, yz, zz), in that order.
  double f[15][Set::kValues];
  /// Of H: 1, M, a (3).
  double h[5][Set::kValues];
  std::size_t samples = 0; ///< how many samples they hold (0: nothing to add)
};

/// The points [first, last) of the pyramid, read one by one by a walk.
struct PointSpan
{
  std::uint32_t first, last;
};

/// A point of a walk as every point of its region reads it (packWalk in src/multiresolution/MultiresolutionPacking.h):
/// its position and its fitted values f (MomentSet.h) about the region's corner.
template <typename Set, bool Padded = AggregateMomentsT<Set>::kStride != Set::kValues>
struct PackedPointT
{
  Vec3 position;
  double sums[Set::kValues];
};

/// The same for a set whose moments' rows are padded (AggregateMomentsT::kStride): its values first, on whole
/// four-double vectors, so that the kernel's vector adds read them aligned.
template <typename Set>
struct alignas(32) PackedPointT<Set, true>
{
  double sums[AggregateMomentsT<Set>::kStride];
  Vec3 position;
};

/// A cell of a walk as every point of its region reads it once the cell is classified (its placement and spread are
/// in CellPlacements): its CellSample about the region's corner, on cache lines of its own.
template <typename Set>
struct alignas(64) PackedCellT
{
  CellSampleT<Set> sample;
};

/// What places each packed cell in the shells for a point and splits its spread into shell pieces, one array per
/// value (the loops over every cell for every point read these, four cells at a time in the AVX2 build): the
/// centroid, sample.spreadPerPoint, sample.halfWidth and spreadDensity(halfWidth) (zeros where the half-width is 0),
/// in packedCells' order.
struct CellPlacements
{
  std::vector<double> x, y, z, spreadPerPoint, halfWidth, rho, gradientScale;

  void resize(std::size_t n)
  {
    for (std::vector<double>* v : { &x, &y, &z, &spreadPerPoint, &halfWidth, &rho, &gradientScale })
    {
      v->resize(n);
    }
  }

  /// The spread density of cell i.
  SpreadDensity density(std::size_t i) const { return { rho[i], gradientScale[i] }; }

  void set(std::size_t i, const Vec3& centroid, double spread, double half)
  {
    x[i] = centroid.x;
    y[i] = centroid.y;
    z[i] = centroid.z;
    spreadPerPoint[i] = spread;
    halfWidth[i] = half;
    const SpreadDensity d = half > 0.0 ? spreadDensity(half) : SpreadDensity{ 0.0, 0.0 };
    rho[i] = d.rho;
    gradientScale[i] = d.gradientScale;
  }
};

/// The part of a thread's scratch of evaluateAllScalesMultiresolutionOnCpu that no moment set changes: the walks'
/// lists and keys, and the placements and kinds of the packed cells (MultiresolutionScratchT holds the rest).
struct MultiresolutionWalkScratch
{
  std::vector<std::uint32_t> frontier, next, opened, taken;
  std::vector<PointSpan> read; ///< the points read one by one, as ranges [first, last) of the pyramid's points
  std::vector<int> takenLevel;
  CellPlacements placements;
  std::vector<double> cellMean;
  std::vector<int> cellShell;
  std::vector<std::uint32_t> singleCells, pairCells, spreadCells, wideCells;
  std::vector<std::uint8_t> takenFar; ///< per taken cell: decided by a far part's rule (never read point by point)
  /// The cells where the walk of far part 1 (farKey[0]) left off for the walk region's own walk (part 0), level by
  /// level from the top: those of no far part (the near subtrees) and the far cells taken whole but not linearized.
  /// A walk region's walk starts from them instead of the top cells: the cells above them are decided from F_0 alone,
  /// as every region of F_0 would decide them.
  std::vector<std::uint32_t> nearSeeds;
  std::vector<int> nearSeedLevel;
  /// Per far part, the cells of its walk taken whole but too narrow to linearize (linearizable): every walk region of
  /// its far region samples them as near cells.
  std::vector<std::uint32_t> farSampled[kMaxFarLevels];
  std::vector<int> farSampledLevel[kMaxFarLevels];
  bool walked = false, farWalked[kMaxFarLevels] = {};
  WalkKey walkedKey{}, farKey[kMaxFarLevels] = {};
};

/// Per-thread scratch of evaluateAllScalesMultiresolutionOnCpu (reused across points), for the moment set Set. It
/// keeps the last walk (the samples of one walkRegion, shared by the points of that region: consecutive points in
/// pyramid order mostly share it) with its key; a scratch reused for another pyramid at the same address with the
/// same count and accuracy must be reset (`walked = false`).
template <typename Set>
struct MultiresolutionScratchT : MultiresolutionWalkScratch
{
  std::vector<AggregateMomentsT<Set>> bins;
  std::vector<PackedPointT<Set>> packedPoints;
  std::vector<PackedCellT<Set>> packedCells;
  InnerSumsT<Set> inner; ///< the walk's samples within the first shell for its whole region (not in packedCells/Points)
  LinearizedBinsT<Set> linearized[kMaxFarLevels]; ///< of each far part's region (farKey[i].farRegion)
};

/// The oriented sphere's kernel types.
using LinearizedBins = LinearizedBinsT<OrientedSphereMoments>;
using InnerSums = InnerSumsT<OrientedSphereMoments>;
using PackedPoint = PackedPointT<OrientedSphereMoments>;
using PackedCell = PackedCellT<OrientedSphereMoments>;
using MultiresolutionScratch = MultiresolutionScratchT<OrientedSphereMoments>;

/// Fits every scale of the evaluation point p, as evaluateAllScalesMultiresolution; out: S samples.
void evaluateAllScalesMultiresolutionOnCpu(const MultiresolutionView& v, const Vec3& p, const ScaleBinning& b,
  double minNeighbors, MultiresolutionScratch& scratch, ScaleSample* out,
  CpuKernelBuild build = CpuKernelBuild::Fastest);

/// The same with the principal curvatures (ShapeOperatorMoments), from the curvature set's cell sums (cells:
/// summedCellsOf<ShapeOperatorMoments> of the pyramid); out: S curvature samples.
void evaluateAllScalesMultiresolutionOnCpu(const MultiresolutionView& v, const CurvatureCell* cells, const Vec3& p,
  const ScaleBinning& b, double minNeighbors, MultiresolutionScratchT<ShapeOperatorMoments>& scratch,
  CurvatureSample* out, CpuKernelBuild build = CpuKernelBuild::Fastest);

} // namespace gls
