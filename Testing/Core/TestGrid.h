// The exact evaluation's grid over a test cloud, built as the engine builds it (normals normalized, the points with a
// non-finite coordinate or a zero normal left out), for tests that call a per-point kernel directly.
#pragma once

#include "TestClouds.h"

#include "gls/NeighborGrid.h"

#include <vector>

namespace glstest
{

/// The grid of the cloud's admitted points with unit normals, cells of `cellSize` (a quarter of the largest scale,
/// as the engine's).
struct TestGrid
{
  TestGrid(const Cloud& c, double cellSize)
  {
    gls::normalizeAndAdmit(c.points.data(), c.normals.data(), c.size(), this->UnitNormals, this->Admit);
    this->Grid.build(c.points.data(), this->UnitNormals.data(), c.size(), cellSize, this->Admit.data());
  }
  TestGrid(const TestGrid&) = delete;
  TestGrid& operator=(const TestGrid&) = delete;
  const gls::GridView& view() const { return this->Grid.view(); }

  std::vector<double> UnitNormals;
  std::vector<unsigned char> Admit;
  gls::NeighborGrid Grid;
};

} // namespace glstest
