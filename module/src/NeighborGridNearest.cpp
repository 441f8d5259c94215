// The k-nearest queries of NeighborGrid: one query at a time (rings of cells around the query's cell, cells and rows
// farther than the k-th kept point skipped), and the queries of a run of points of one cell together (the cell's
// neighbourhood gathered once, each answer the one query's where no point outside it can enter).
#include "gls/NeighborGrid.h"

#include "gls/Numeric.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gls
{
namespace
{

/// The k nearest points offered so far (k: `want`), kept sorted by (squared distance, original index), nearest
/// first, in `out`'s storage (sized once; finish() gives `out` its final size): a candidate enters by insertion (the
/// few that beat the current k-th), most are rejected by one comparison with the k-th's distance.
class NearestKept
{
public:
  NearestKept(const std::uint64_t* ids, std::size_t want, std::vector<std::pair<double, std::uint64_t>>& out)
    : Ids(ids)
    , Want(want)
    , Out(out)
  {
    out.resize(want);
    this->Kept = out.data();
  }

  void offer(double d2, std::uint64_t i)
  {
    std::size_t j = this->Size;
    if (j == this->Want)
    {
      if (d2 > this->Kept[j - 1].first || !this->Closer(d2, i, this->Kept[j - 1]))
      {
        return;
      }
      --j;
    }
    else
    {
      ++this->Size;
    }
    for (; j > 0 && this->Closer(d2, i, this->Kept[j - 1]); --j)
    {
      this->Kept[j] = this->Kept[j - 1];
    }
    this->Kept[j] = { d2, i };
  }

  bool full() const { return this->Size == this->Want; }

  /// The squared distance below which no unvisited point can beat the k-th kept one (infinity until k are kept).
  double worst() const
  {
    return this->full() ? this->Kept[this->Size - 1].first : std::numeric_limits<double>::infinity();
  }

  /// Gives `out` the kept points only.
  void finish() { this->Out.resize(this->Size); }

private:
  bool Closer(double d2, std::uint64_t i, const std::pair<double, std::uint64_t>& o) const
  {
    return d2 < o.first || (d2 == o.first && this->Ids[i] < this->Ids[o.second]);
  }

  const std::uint64_t* Ids;
  std::size_t Want;
  std::vector<std::pair<double, std::uint64_t>>& Out;
  std::pair<double, std::uint64_t>* Kept = nullptr;
  std::size_t Size = 0;
};

/// The square of kNearestOfCellRun's factor on the previous query's k-th distance (1.2: at 1M points of the bunny,
/// 451 ns a query against 640 ns with a true bound, the previous k-th distance plus the step between the queries).
constexpr double kGuessSquared = 1.2 * 1.2;

/// Above this many points per neighbour asked in a run's cell and the cells around it, its queries go one at a time
/// (kNearest), and nothing is gathered: on the bunny at 10M points a run's cells hold about 12 per neighbour (k = 16);
/// with a dense blob (200,000 points in 1 mm inside 400,000 of the bunny) every query offered everything gathered
/// cost 76 us against kNearest's 22 us (the blob's cells hold thousands); with this limit both take 19 us.
constexpr std::size_t kMostRunCandidatesPerNeighbor = 32;

/// One k-nearest query's walk over rings of cells around the query's cell (kNearest): cells and rows farther from c
/// than the k-th kept point are skipped. Their distance is computed from the cell bounds origin + index * cellSize,
/// less a margin far above the rounding of those bounds and of the cells the points were sorted into (that of
/// ballCellBlock), so no point that could enter is skipped.
class RingSearch
{
public:
  RingSearch(const GridView& g, const Vec3& c, NearestKept& kept, const unsigned char* admitSorted)
    : G(g)
    , C(c)
    , Kept(kept)
    , AdmitSorted(admitSorted)
    , Cc{ gridCellOf(g, c.x, 0), gridCellOf(g, c.y, 1), gridCellOf(g, c.z, 2) }
    , Bounds(ballCellBlock(g, c, 0.0))
    , Prune(Bounds.margin >= 0.0)
  {
  }

  /// Offers the points of ring `ring`'s cells; true when no farther ring can change the answer: every point outside
  /// this ring's block of cells is at least `ring` cells away from c's cell, and once the block covers the grid,
  /// every point was offered (what ends a masked query that admits fewer than k).
  bool visitRing(std::int64_t ring)
  {
    const GridView& g = this->G;
    this->Ring = ring;
    this->Z0 = std::max<std::int64_t>(this->Cc[2] - ring, 0);
    this->Z1 = std::min(this->Cc[2] + ring, g.dims[2] - 1);
    this->Y0 = std::max<std::int64_t>(this->Cc[1] - ring, 0);
    this->Y1 = std::min(this->Cc[1] + ring, g.dims[1] - 1);
    this->Xl = this->Cc[0] - ring;
    this->Xh = this->Cc[0] + ring;
    this->X0 = std::max<std::int64_t>(this->Xl, 0);
    this->X1 = std::min(this->Xh, g.dims[0] - 1);
    // The ring's cells: whole rows where the row is on the ring's shell (z or y at the ring's distance), only the
    // two end cells of the rows inside it (none where both ends are off the grid: a thin grid costs O(1) a ring).
    this->Ends = this->Xl >= 0 || this->Xh < g.dims[0];
    // The layers inside the ring's z range hold ring cells only on the y shell or at the x ends: where neither is
    // on the grid, only the two shell layers are walked.
    if (ring == 0 || this->Cc[1] - ring >= 0 || this->Cc[1] + ring < g.dims[1] || this->Ends)
    {
      for (std::int64_t z = this->Z0; z <= this->Z1; ++z)
      {
        this->visitLayer(z);
      }
    }
    else
    {
      for (const std::int64_t z : { this->Cc[2] - ring, this->Cc[2] + ring })
      {
        if (z >= 0 && z < g.dims[2])
        {
          this->visitLayer(z);
        }
      }
    }
    const double reach = static_cast<double>(ring) * g.cellSize;
    const bool covered = ring >= std::max({ this->Cc[0], g.dims[0] - 1 - this->Cc[0], this->Cc[1],
                                   g.dims[1] - 1 - this->Cc[1], this->Cc[2], g.dims[2] - 1 - this->Cc[2] });
    return (this->Kept.full() && this->Kept.worst() <= reach * reach) || covered;
  }

private:
  /// The squared gap from c to a cell along an axis, less the margin (0 inside it).
  double axisGap(double v, int axis, std::int64_t cell) const
  {
    const double lo = gridCellLowerBound(this->G, axis, cell);
    const double d = distanceToInterval(v, lo, lo + this->G.cellSize) - this->Bounds.margin;
    return d > 0.0 ? d * d : 0.0;
  }

  void visitRun(std::int64_t row, std::int64_t xa, std::int64_t xb)
  {
    const GridView& g = this->G;
    for (std::uint64_t i = gridCellStart(g, row, xa), end = gridCellStart(g, row, xb + 1); i < end; ++i)
    {
      if (this->AdmitSorted == nullptr || this->AdmitSorted[i] != 0)
      {
        this->Kept.offer(squaredNorm(g.points[i] - this->C), i);
      }
    }
  }

  void visitRow(std::int64_t z, std::int64_t y, double gz, bool shell)
  {
    const GridView& g = this->G;
    const double gyz = this->Prune ? gz + this->axisGap(this->C.y, 1, y) : 0.0;
    if (gyz > this->Kept.worst())
    {
      return; // the whole row is farther than the k-th kept point
    }
    const std::int64_t row = z * g.dims[1] + y;
    if (shell)
    {
      // One run of the row's cells, less those at its ends that are too far.
      std::int64_t a = this->X0, b = this->X1;
      while (this->Prune && a <= b && gyz + this->axisGap(this->C.x, 0, a) > this->Kept.worst())
      {
        ++a;
      }
      while (this->Prune && b >= a && gyz + this->axisGap(this->C.x, 0, b) > this->Kept.worst())
      {
        --b;
      }
      if (a <= b)
      {
        this->visitRun(row, a, b);
      }
      return;
    }
    for (const std::int64_t x : { this->Xl, this->Xh })
    {
      if (x >= 0 && x < g.dims[0] && (x == this->Xl || this->Xh != this->Xl) &&
        (!this->Prune || gyz + this->axisGap(this->C.x, 0, x) <= this->Kept.worst()))
      {
        this->visitRun(row, x, x);
      }
    }
  }

  void visitLayer(std::int64_t z)
  {
    const GridView& g = this->G;
    const std::int64_t ring = this->Ring;
    const double gz = this->Prune ? this->axisGap(this->C.z, 2, z) : 0.0;
    if (std::abs(z - this->Cc[2]) == ring)
    {
      for (std::int64_t y = this->Y0; y <= this->Y1; ++y)
      {
        this->visitRow(z, y, gz, true);
      }
      return;
    }
    for (const std::int64_t y : { this->Cc[1] - ring, this->Cc[1] + ring })
    {
      if (y >= 0 && y < g.dims[1])
      {
        this->visitRow(z, y, gz, true);
      }
    }
    for (std::int64_t y = std::max(this->Y0, this->Cc[1] - ring + 1);
         this->Ends && y <= std::min(this->Y1, this->Cc[1] + ring - 1); ++y)
    {
      this->visitRow(z, y, gz, false);
    }
  }

  const GridView& G;
  const Vec3 C;
  NearestKept& Kept;
  const unsigned char* AdmitSorted;
  const std::int64_t Cc[3];
  const CellBlock Bounds;
  const bool Prune;
  std::int64_t Ring = 0, Z0 = 0, Z1 = 0, Y0 = 0, Y1 = 0, Xl = 0, Xh = 0, X0 = 0, X1 = 0;
  bool Ends = false;
};

/// The block of cells around a run's cell (the cell and its 26 neighbours, clamped to the grid).
struct RunBlock
{
  std::int64_t lo[3], hi[3];
};

RunBlock runBlockAround(const GridView& g, const Vec3& p)
{
  const double c[3] = { p.x, p.y, p.z };
  RunBlock b;
  for (int a = 0; a < 3; ++a)
  {
    const std::int64_t cell = gridCellOf(g, c[a], a);
    b.lo[a] = std::max<std::int64_t>(cell - 1, 0);
    b.hi[a] = std::min(cell + 1, g.dims[a] - 1);
  }
  return b;
}

/// Calls f(first, end) for the sorted points of each row of the block.
template <typename F>
void forEachBlockRow(const GridView& g, const RunBlock& b, F&& f)
{
  for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
  {
    for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
    {
      const std::int64_t row = z * g.dims[1] + y;
      f(gridCellStart(g, row, b.lo[0]), gridCellStart(g, row, b.hi[0] + 1));
    }
  }
}

/// The block's points into the scratch's coordinate columns and indices (in the order kNearest would not need: the
/// answer does not depend on the order in which points are offered).
void gatherBlock(const GridView& g, const RunBlock& b, NeighborGrid::CellRunScratch& scratch)
{
  scratch.x.clear();
  scratch.y.clear();
  scratch.z.clear();
  scratch.index.clear();
  forEachBlockRow(g, b, [&](std::uint64_t first, std::uint64_t end) {
    for (std::uint64_t i = first; i < end; ++i)
    {
      scratch.x.push_back(g.points[i].x);
      scratch.y.push_back(g.points[i].y);
      scratch.z.push_back(g.points[i].z);
      scratch.index.push_back(i);
    }
  });
  scratch.d2.resize(scratch.index.size());
  scratch.selected.resize(scratch.index.size());
}

/// The `want` nearest of the gathered points to p into scratch.out, and their k-th distance as the next guess. A
/// guess of the k-th distance: 1.2 times the previous query's (of this run, or the scratch's last one; a point's
/// k-th distance is close to its neighbour's on a sampled surface). Only the candidates within it are offered: where
/// at least k are, the k nearest are among them. Where fewer are, all are offered.
void nearestGathered(const GridView& g, const Vec3& p, std::size_t want, NeighborGrid::CellRunScratch& scratch)
{
  const std::size_t candidates = scratch.index.size();
  // The squared distances as kNearest computes them (squaredNorm(point - p)), in a loop the compiler vectorizes.
  const double* x = scratch.x.data();
  const double* y = scratch.y.data();
  const double* z = scratch.z.data();
  double* d2 = scratch.d2.data();
  for (std::size_t j = 0; j < candidates; ++j)
  {
    const double dx = x[j] - p.x, dy = y[j] - p.y, dz = z[j] - p.z;
    d2[j] = dx * dx + dy * dy + dz * dz;
  }
  const double bound =
    scratch.previousKth >= 0.0 ? kGuessSquared * scratch.previousKth : std::numeric_limits<double>::infinity();
  // The candidates within the bound, gathered without a branch; all of them where fewer than k are.
  std::size_t* selected = scratch.selected.data();
  std::size_t within = 0;
  for (std::size_t j = 0; j < candidates; ++j)
  {
    selected[within] = j;
    within += d2[j] <= bound ? 1 : 0;
  }
  if (within < want)
  {
    for (std::size_t j = 0; j < candidates; ++j)
    {
      selected[j] = j;
    }
    within = candidates;
  }
  NearestKept kept(g.ids, want, scratch.out);
  for (std::size_t m = 0; m < within; ++m)
  {
    kept.offer(d2[selected[m]], scratch.index[selected[m]]);
  }
  kept.finish();
  scratch.previousKth = scratch.out.size() == want ? scratch.out.back().first : -1.0;
}

/// Whether the block's answer for p is whole: no point outside the block is nearer than the block's nearest face
/// that is not the grid's edge (less the margin of the cells' rounding, that of ballCellBlock), so where the k-th kept
/// point is nearer than that face, no point outside could enter.
bool wholeInBlock(const GridView& g, const Vec3& p, const RunBlock& b, std::size_t want,
  const std::vector<std::pair<double, std::uint64_t>>& out)
{
  const CellBlock bounds = ballCellBlock(g, p, 0.0);
  if (out.size() != want || !(bounds.margin >= 0.0))
  {
    return false;
  }
  const double pc[3] = { p.x, p.y, p.z };
  double face = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
  {
    if (b.lo[a] > 0)
    {
      face = std::min(face, pc[a] - gridCellLowerBound(g, a, b.lo[a]));
    }
    if (b.hi[a] < g.dims[a] - 1)
    {
      face = std::min(face, gridCellLowerBound(g, a, b.hi[a] + 1) - pc[a]);
    }
  }
  face -= bounds.margin;
  return face > 0.0 && out.back().first < face * face;
}

} // namespace

void NeighborGrid::kNearest(const Vec3& c, int k, std::vector<std::pair<double, std::uint64_t>>& out,
  const unsigned char* admitSorted) const
{
  out.clear();
  const GridView& g = this->View;
  if (k <= 0 || g.count == 0)
  {
    return;
  }
  NearestKept kept(g.ids, std::min<std::size_t>(static_cast<std::size_t>(k), g.count), out);
  RingSearch search(g, c, kept, admitSorted);
  const std::int64_t maxRing = std::max({ g.dims[0], g.dims[1], g.dims[2] });
  for (std::int64_t ring = 0; ring <= maxRing && !search.visitRing(ring); ++ring)
  {
  }
  kept.finish();
}

std::uint64_t NeighborGrid::cellRunEnd(std::uint64_t first) const
{
  const GridView& g = this->View;
  const Vec3& p = g.points[first];
  return gridCellStart(g, gridCellOf(g, p.z, 2) * g.dims[1] + gridCellOf(g, p.y, 1), gridCellOf(g, p.x, 0) + 1);
}

void NeighborGrid::kNearestOfCellRun(std::uint64_t first, std::uint64_t last, int k, CellRunScratch& scratch,
  const std::function<void(std::uint64_t, const std::vector<std::pair<double, std::uint64_t>>&)>& visit) const
{
  const GridView& g = this->View;
  if (first >= last)
  {
    return;
  }
  if (k <= 0)
  {
    scratch.out.clear();
    for (std::uint64_t s = first; s < last; ++s)
    {
      visit(s, scratch.out);
    }
    return;
  }
  const RunBlock block = runBlockAround(g, g.points[first]);
  const std::size_t want = std::min<std::size_t>(static_cast<std::size_t>(k), g.count);
  std::size_t gathered = 0;
  forEachBlockRow(g, block, [&gathered](std::uint64_t begin, std::uint64_t end) { gathered += end - begin; });
  if (gathered > kMostRunCandidatesPerNeighbor * want)
  {
    // Crowded cells (a scanner's near field): each query offered every point around would cost more than
    // kNearest, which stops at the cells its k-th reaches. Nothing is gathered.
    for (std::uint64_t s = first; s < last; ++s)
    {
      this->kNearest(g.points[s], k, scratch.out);
      scratch.previousKth = scratch.out.size() == want ? scratch.out.back().first : -1.0;
      visit(s, scratch.out);
    }
    return;
  }
  gatherBlock(g, block, scratch);
  for (std::uint64_t s = first; s < last; ++s)
  {
    const Vec3 p = g.points[s];
    nearestGathered(g, p, want, scratch);
    if (!wholeInBlock(g, p, block, want, scratch.out))
    {
      this->kNearest(p, k, scratch.out);
    }
    visit(s, scratch.out);
  }
}

} // namespace gls
