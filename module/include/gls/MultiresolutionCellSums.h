// The sums a pyramid keeps for its cells of level summedLevel and above (cellMoments' `cells`), for any moment set:
// the rule the build forms the pyramid's own (the oriented sphere's) with, and the same rule over a built pyramid for
// another set, whose walks and kernels then read them (MultiresolutionReferenceWalk.h, MultiresolutionKernel.h).
#pragma once

#include "gls/CellMoments.h"
#include "gls/MultiresolutionTakeWhole.h"
#include "gls/MultiresolutionView.h"
#include "gls/ParallelFor.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gls
{

/// The sums of the cell `node` (of level `level` >= summedLevel, lower corner `corner`) that the moment set Set keeps:
/// at level summedLevel from its points (momentsOfPoints about its corner), above it merged from its children's
/// (mergeChildren about its corner; cells: node i's at cells[i - summedBegin], its children's formed first).
template <typename Set>
void formSummedCell(const PyramidNode* nodes, const StoredPoints& points, std::uint64_t summedBegin, int summedLevel,
  std::uint32_t node, int level, const Vec3& corner, typename Set::Cell* cells)
{
  typename Set::Cell& cell = cells[node - summedBegin];
  if (level == summedLevel)
  {
    std::uint32_t first = 0, last = 0;
    pointRange(nodes, node, level, first, last);
    momentsOfPoints<Set>(points, first, last, corner, cell);
    return;
  }
  const PyramidNode& n = nodes[node];
  mergeChildren<Set>(cells + (n.first - summedBegin), n.last - n.first, corner, cell);
}

/// The sums the moment set Set keeps for every cell of a built pyramid's levels summedLevel and above, node i's at
/// [i - summedBegin], formed level by level from the finest as the build forms the pyramid's own (for Set =
/// OrientedSphereMoments they equal v.cells bit for bit). On `parallel`'s threads (the same sums whatever their count).
template <typename Set>
std::vector<typename Set::Cell> summedCellsOf(const MultiresolutionView& v, const ParallelOptions& parallel = {})
{
  std::vector<typename Set::Cell> cells(static_cast<std::size_t>(v.topEnd - v.summedBegin));
  // Levels are stored finest first, each contiguous: level l - 1 begins at the first child of level l's first node.
  std::vector<std::uint64_t> levelBegin(static_cast<std::size_t>(v.topLevel) + 2);
  levelBegin[v.topLevel] = v.topBegin;
  levelBegin[v.topLevel + 1] = v.topEnd;
  for (int l = v.topLevel; l > v.summedLevel; --l)
  {
    levelBegin[l - 1] = v.nodes[levelBegin[l]].first;
  }
  for (int level = v.summedLevel; level <= v.topLevel; ++level)
  {
    const std::uint64_t first = levelBegin[level];
    parallelFor(levelBegin[level + 1] - first, parallel, [&](std::size_t b, std::size_t e, int) {
      for (std::size_t k = b; k < e; ++k)
      {
        const auto node = static_cast<std::uint32_t>(first + k);
        formSummedCell<Set>(v.nodes, v.points, v.summedBegin, v.summedLevel, node, level,
          nodeCorner(v.origin, v.nodes[node], v.levelSize[level]), cells.data());
      }
    });
  }
  return cells;
}

} // namespace gls
