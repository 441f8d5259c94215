// Private to the CPU multi-resolution kernel (MultiresolutionKernel.cpp, its only includer): the walks that find a
// point's samples level by level (the walk region's own and each far part's), and the keys that tell when the last
// walk can be reused.
#pragma once

#include "gls/MultiresolutionKernel.h"

#include <cstdint>

namespace gls
{
namespace kernel
{

/// What the cells of one walk are compared with: the walk's part and region, the far rule, and the squared radius,
/// accuracy and smallest scale.
struct WalkTarget
{
  const MultiresolutionView& v;
  const WalkRegion& region;
  const FarRule& far;
  int part;
  double r2, eps2, floor2;
};

/// One level of a walk: each cell of the frontier is skipped (outside every ball of the region, or not this part's),
/// taken whole (appended to s.taken from `takenBefore`; the end is returned in `taken`) or opened (the first
/// `opened` of s.opened, returned); part 1 also records where part 0 takes over (s.nearSeeds). The writes only
/// advance indices: no branch per cell.
GLS_FORCE_INLINE std::size_t classifyLevel(
  const WalkTarget& w, int level, std::size_t takenBefore, std::size_t& taken, MultiresolutionWalkScratch& s)
{
  const bool recordSeeds = w.part == 1;
  const double edge = w.v.levelSize[level];
  const double edge2 = edge * edge;
  const std::size_t n = s.frontier.size();
  s.taken.resize(takenBefore + n);
  s.takenFar.resize(takenBefore + n);
  s.opened.resize(n);
  if (recordSeeds)
  {
    s.nearSeeds.resize(s.nearSeedLevel.size() + n);
  }
  std::size_t opened = 0, seedCount = s.nearSeedLevel.size();
  taken = takenBefore;
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::uint32_t c = s.frontier[i];
    const CellPlace place = placeCell(w.far, w.region, nodeCorner(w.v.origin, w.v.nodes[c], edge), edge);
    const bool mine = w.part == 0 || place.far >= w.part;
    const bool inside = mine && place.box2 < w.r2;
    const bool whole = takenWhole(edge2, place.box2, w.eps2, w.floor2);
    const bool sample = place.linearized == w.part;
    s.taken[taken] = c;
    s.takenFar[taken] = place.far > 0 ? 1 : 0;
    taken += inside && whole && sample ? 1 : 0;
    s.opened[opened] = c;
    opened += inside && !whole ? 1 : 0;
    if (recordSeeds)
    {
      // Part 0's from here: a cell of no far part (its distance is the walk region's), a far cell it samples, or a
      // far cell of level 0 it reads point by point.
      s.nearSeeds[seedCount] = c;
      seedCount += !mine || (inside && (whole ? place.linearized == 0 : level == 0)) ? 1 : 0;
    }
  }
  if (recordSeeds)
  {
    s.nearSeeds.resize(seedCount);
    s.nearSeedLevel.resize(seedCount, level);
  }
  return opened;
}

/// The near cells taken whole at this level (s.taken[takenBefore, taken)) that hold too few points for a sample are
/// read point by point instead (readPointByPoint; s.read); the others stay, with their level.
GLS_FORCE_INLINE void readSmallNearCells(
  const MultiresolutionView& v, int level, std::size_t takenBefore, std::size_t taken, MultiresolutionWalkScratch& s)
{
  std::size_t kept = takenBefore;
  for (std::size_t i = takenBefore; i < taken; ++i)
  {
    const std::uint32_t c = s.taken[i];
    PointSpan span{};
    if (!s.takenFar[i] && readPointByPoint(v, c, level, span.first, span.last))
    {
      s.read.push_back(span);
    }
    else
    {
      s.taken[kept] = c;
      s.takenFar[kept] = s.takenFar[i];
      ++kept;
    }
  }
  s.taken.resize(kept);
  s.takenFar.resize(kept);
  s.takenLevel.resize(kept, level);
}

/// The children of the `opened` cells opened at a level above 0: the next level's frontier.
GLS_FORCE_INLINE void openCells(const MultiresolutionView& v, std::size_t opened, MultiresolutionWalkScratch& s)
{
  s.next.clear();
  for (std::size_t i = 0; i < opened; ++i)
  {
    const PyramidNode& node = v.nodes[s.opened[i]];
    for (std::uint32_t c = node.first; c < node.last; ++c)
    {
      s.next.push_back(c);
    }
  }
  s.frontier.swap(s.next);
}

/// The walks of the CPU kernel (forEachMultiresolutionSample's rule, FarRule): a point's samples are those of its
/// walk region's own walk (part 0: every sample but the linearized cells) and of each far part i's walk (part i + 1:
/// its linearized cells, the same for every point of its far region).
///
/// A walk, level by level (classifyLevel): each cell of the frontier is skipped, taken whole (s.taken, s.takenLevel),
/// read point by point (s.read, part 0 only: a level-0 cell not taken whole, or a near cell taken whole that holds too
/// few points for a sample: readSmallNearCells) or opened (its children make the next level's frontier: openCells). A
/// far part's walk goes through the cells of its part and of the larger ones only (a cell's part is at most its
/// parent's); part 1's records where part 0 takes over (s.nearSeeds). With `seeded`, part 0 starts from those instead
/// of the top cells, each joining the frontier at its level (the cells above them are far cells opened, or
/// linearized, by F_0's rule for every point of F_0).
GLS_FORCE_INLINE void walk(const MultiresolutionView& v, const WalkRegion& region, const FarRule& far, int part,
  bool seeded, double r, double smallest, MultiresolutionWalkScratch& s)
{
  s.taken.clear();
  s.takenLevel.clear();
  s.takenFar.clear();
  s.read.clear();
  s.frontier.clear();
  if (part == 1)
  {
    s.nearSeeds.clear();
    s.nearSeedLevel.clear();
  }
  const WalkTarget target{ v, region, far, part, r * r, v.accuracy * v.accuracy, smallest * smallest };
  if (!seeded && v.topEnd > v.topBegin && r > 0.0)
  {
    forEachTopCell(v, outermostRegion(far, region), r, [&](std::uint32_t c) { s.frontier.push_back(c); });
  }
  std::size_t seed = 0;
  const std::size_t seeds = seeded ? s.nearSeeds.size() : 0;
  for (int level = v.topLevel; level >= 0 && (!s.frontier.empty() || seed < seeds); --level)
  {
    for (; seed < seeds && s.nearSeedLevel[seed] == level; ++seed)
    {
      s.frontier.push_back(s.nearSeeds[seed]);
    }
    const std::size_t takenBefore = s.taken.size();
    std::size_t taken = takenBefore;
    const std::size_t opened = classifyLevel(target, level, takenBefore, taken, s);
    readSmallNearCells(v, level, takenBefore, taken, s);
    if (level == 0)
    {
      for (std::size_t i = 0; i < opened && part == 0; ++i)
      {
        const PyramidNode& node = v.nodes[s.opened[i]];
        s.read.push_back({ node.first, node.last });
      }
      break;
    }
    openCells(v, opened, s);
  }
}

GLS_FORCE_INLINE bool sameRegion(const WalkRegion& a, const WalkRegion& b)
{
  return a.edge == b.edge && a.corner.x == b.corner.x && a.corner.y == b.corner.y && a.corner.z == b.corner.z;
}

/// The same far walk: the same key but perhaps another walk region of the same far region (the region first: it is
/// what changes from one point to the next).
GLS_FORCE_INLINE bool sameFarWalk(const WalkKey& a, const WalkKey& b)
{
  return sameRegion(a.farRegion, b.farRegion) && a.nodes == b.nodes && a.count == b.count &&
    a.accuracy == b.accuracy && a.radius == b.radius && a.smallest == b.smallest &&
    a.linearizedDistance == b.linearizedDistance && a.squaredScales == b.squaredScales && a.scaleCount == b.scaleCount;
}

GLS_FORCE_INLINE bool sameWalk(const WalkKey& a, const WalkKey& b)
{
  return sameFarWalk(a, b) && sameRegion(a.region, b.region);
}

} // namespace kernel
} // namespace gls
