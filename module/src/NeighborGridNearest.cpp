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
  const auto offer = [&kept](double d2, std::uint64_t i) { kept.offer(d2, i); };
  const auto worst = [&kept]() { return kept.worst(); };

  const std::int64_t cc[3] = { gridCellOf(g, c.x, 0), gridCellOf(g, c.y, 1), gridCellOf(g, c.z, 2) };
  const std::int64_t maxRing = std::max({ g.dims[0], g.dims[1], g.dims[2] });
  // Cells and rows farther from c than the k-th kept point are skipped. Their distance is computed from the cell
  // bounds origin + index * cellSize, less a margin far above the rounding of those bounds and of the cells the
  // points were sorted into (that of ballCellBlock), so no point that could enter is skipped.
  const CellBlock bounds = ballCellBlock(g, c, 0.0);
  const bool prune = bounds.margin >= 0.0;
  const auto axisGap = [&](double v, int axis, std::int64_t cell) {
    const double lo = gridCellLowerBound(g, axis, cell);
    const double d = distanceToInterval(v, lo, lo + g.cellSize) - bounds.margin;
    return d > 0.0 ? d * d : 0.0;
  };
  const auto visitRun = [&](std::int64_t row, std::int64_t xa, std::int64_t xb) {
    for (std::uint64_t i = g.cellStart[row + xa]; i < g.cellStart[row + xb + 1]; ++i)
    {
      if (admitSorted == nullptr || admitSorted[i] != 0)
      {
        offer(squaredNorm(g.points[i] - c), i);
      }
    }
  };

  for (std::int64_t ring = 0; ring <= maxRing; ++ring)
  {
    const std::int64_t z0 = std::max<std::int64_t>(cc[2] - ring, 0), z1 = std::min(cc[2] + ring, g.dims[2] - 1);
    const std::int64_t y0 = std::max<std::int64_t>(cc[1] - ring, 0), y1 = std::min(cc[1] + ring, g.dims[1] - 1);
    const std::int64_t xl = cc[0] - ring, xh = cc[0] + ring;
    const std::int64_t x0 = std::max<std::int64_t>(xl, 0), x1 = std::min(xh, g.dims[0] - 1);
    // The ring's cells: whole rows where the row is on the ring's shell (z or y at the ring's distance), only the
    // two end cells of the rows inside it (none where both ends are off the grid: a thin grid costs O(1) a ring).
    const bool ends = xl >= 0 || xh < g.dims[0];
    const auto visitRow = [&](std::int64_t z, std::int64_t y, double gz, bool shell) {
      const double gyz = prune ? gz + axisGap(c.y, 1, y) : 0.0;
      if (gyz > worst())
      {
        return; // the whole row is farther than the k-th kept point
      }
      const std::int64_t row = (z * g.dims[1] + y) * g.dims[0];
      if (shell)
      {
        // One run of the row's cells, less those at its ends that are too far.
        std::int64_t a = x0, b = x1;
        while (prune && a <= b && gyz + axisGap(c.x, 0, a) > worst())
        {
          ++a;
        }
        while (prune && b >= a && gyz + axisGap(c.x, 0, b) > worst())
        {
          --b;
        }
        if (a <= b)
        {
          visitRun(row, a, b);
        }
        return;
      }
      for (const std::int64_t x : { xl, xh })
      {
        if (x >= 0 && x < g.dims[0] && (x == xl || xh != xl) &&
          (!prune || gyz + axisGap(c.x, 0, x) <= worst()))
        {
          visitRun(row, x, x);
        }
      }
    };
    const auto visitLayer = [&](std::int64_t z) {
      const double gz = prune ? axisGap(c.z, 2, z) : 0.0;
      if (std::abs(z - cc[2]) == ring)
      {
        for (std::int64_t y = y0; y <= y1; ++y)
        {
          visitRow(z, y, gz, true);
        }
        return;
      }
      for (const std::int64_t y : { cc[1] - ring, cc[1] + ring })
      {
        if (y >= 0 && y < g.dims[1])
        {
          visitRow(z, y, gz, true);
        }
      }
      for (std::int64_t y = std::max(y0, cc[1] - ring + 1); ends && y <= std::min(y1, cc[1] + ring - 1); ++y)
      {
        visitRow(z, y, gz, false);
      }
    };
    // The layers inside the ring's z range hold ring cells only on the y shell or at the x ends: where neither is
    // on the grid, only the two shell layers are walked.
    if (ring == 0 || cc[1] - ring >= 0 || cc[1] + ring < g.dims[1] || ends)
    {
      for (std::int64_t z = z0; z <= z1; ++z)
      {
        visitLayer(z);
      }
    }
    else
    {
      for (const std::int64_t z : { cc[2] - ring, cc[2] + ring })
      {
        if (z >= 0 && z < g.dims[2])
        {
          visitLayer(z);
        }
      }
    }
    // Every point outside this ring's block of cells is at least `ring` cells away from c's cell; once the block
    // covers the grid, every point was offered (what ends a masked query that admits fewer than k).
    const double reach = static_cast<double>(ring) * g.cellSize;
    const bool covered = ring >= std::max({ cc[0], g.dims[0] - 1 - cc[0], cc[1], g.dims[1] - 1 - cc[1], cc[2],
                                   g.dims[2] - 1 - cc[2] });
    if ((kept.full() && kept.worst() <= reach * reach) || covered)
    {
      break;
    }
  }
  kept.finish();
}

std::uint64_t NeighborGrid::cellRunEnd(std::uint64_t first) const
{
  const GridView& g = this->View;
  const Vec3& p = g.points[first];
  const std::int64_t cell =
    (gridCellOf(g, p.z, 2) * g.dims[1] + gridCellOf(g, p.y, 1)) * g.dims[0] + gridCellOf(g, p.x, 0);
  return g.cellStart[cell + 1];
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
  // The block of the run's cell and the cells around it (clamped to the grid), its points gathered in the order
  // kNearest would not need: the answer does not depend on the order in which points are offered.
  const Vec3& p0 = g.points[first];
  const double c0[3] = { p0.x, p0.y, p0.z };
  std::int64_t lo[3], hi[3];
  for (int a = 0; a < 3; ++a)
  {
    const std::int64_t c = gridCellOf(g, c0[a], a);
    lo[a] = std::max<std::int64_t>(c - 1, 0);
    hi[a] = std::min(c + 1, g.dims[a] - 1);
  }
  const std::size_t want = std::min<std::size_t>(static_cast<std::size_t>(k), g.count);
  std::size_t gathered = 0;
  for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
  {
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
    {
      const std::int64_t row = (z * g.dims[1] + y) * g.dims[0];
      gathered += g.cellStart[row + hi[0] + 1] - g.cellStart[row + lo[0]];
    }
  }
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
  scratch.x.clear();
  scratch.y.clear();
  scratch.z.clear();
  scratch.index.clear();
  for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
  {
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
    {
      const std::int64_t row = (z * g.dims[1] + y) * g.dims[0];
      for (std::uint64_t i = g.cellStart[row + lo[0]]; i < g.cellStart[row + hi[0] + 1]; ++i)
      {
        scratch.x.push_back(g.points[i].x);
        scratch.y.push_back(g.points[i].y);
        scratch.z.push_back(g.points[i].z);
        scratch.index.push_back(i);
      }
    }
  }
  const std::size_t candidates = scratch.index.size();
  scratch.d2.resize(candidates);
  scratch.selected.resize(candidates);
  // A guess of the k-th distance: 1.2 times the previous query's (of this run, or the scratch's last one; a point's
  // k-th distance is close to its neighbour's on a sampled surface). Only the candidates within it are offered: where
  // at least k are, the k nearest are among them. Where fewer are, all are offered.
  for (std::uint64_t s = first; s < last; ++s)
  {
    const Vec3 p = g.points[s];
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
    // No point outside the block is nearer than the block's nearest face that is not the grid's edge (less the
    // margin of the cells' rounding, that of ballCellBlock): where the k-th kept point is nearer, the answer is whole.
    const CellBlock bounds = ballCellBlock(g, p, 0.0);
    bool whole = scratch.out.size() == want && bounds.margin >= 0.0;
    const double pc[3] = { p.x, p.y, p.z };
    double face = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3 && whole; ++a)
    {
      if (lo[a] > 0)
      {
        face = std::min(face, pc[a] - gridCellLowerBound(g, a, lo[a]));
      }
      if (hi[a] < g.dims[a] - 1)
      {
        face = std::min(face, gridCellLowerBound(g, a, hi[a] + 1) - pc[a]);
      }
    }
    face -= bounds.margin;
    whole = whole && face > 0.0 && scratch.out.back().first < face * face;
    if (!whole)
    {
      this->kNearest(p, k, scratch.out);
    }
    visit(s, scratch.out);
  }
}

} // namespace gls
