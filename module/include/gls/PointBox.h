// The bounding box of a cloud's finite points: the one rule behind the grids' lattices, the pyramid's frame, the
// suggested cell sizes and a distributed run's bounds.
#pragma once

#include <cstddef>

namespace gls
{

/// The box of the points a cloud counts (length unit): low and high corners over `count` points; both corners 0
/// where no point counts.
struct PointBox
{
  double low[3] = { 0.0, 0.0, 0.0 };
  double high[3] = { 0.0, 0.0, 0.0 };
  std::size_t count = 0;
};

/// The box of the n interleaved positions of xyz that have three finite coordinates and, when `include` is given,
/// a non-zero include[i].
PointBox boxOfFinitePoints(const double* xyz, std::size_t n, const unsigned char* include = nullptr);

} // namespace gls
