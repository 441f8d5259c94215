// The scales' binning for tests that call a per-point kernel directly (the engine builds its own privately).
#pragma once

#include "gls/PointScaleSpace.h"
#include "gls/ScaleSampling.h"

#include <vector>

namespace glstest
{

/// The scales' squared values, binning table and ScaleBinning view, as the engine builds them.
struct TestBinning
{
  explicit TestBinning(const std::vector<double>& scales)
    : Scales(scales)
  {
    for (double t : scales)
    {
      this->Squared.push_back(t * t);
    }
    this->Table = gls::makeBinningTable(this->Squared);
    this->View.scales = this->Scales.data();
    this->View.squaredScales = this->Squared.data();
    this->View.count = static_cast<int>(this->Scales.size());
    this->View.table = this->Table.cells.data();
    this->View.tableSize = static_cast<int>(this->Table.cells.size());
    this->View.inverseCellWidth = this->Table.inverseCellWidth;
  }
  TestBinning(const TestBinning&) = delete;
  TestBinning& operator=(const TestBinning&) = delete;
  std::vector<double> Scales, Squared;
  gls::BinningTable Table;
  gls::ScaleBinning View;
};

} // namespace glstest
