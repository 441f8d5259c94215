#include "gls/SpatialTiles.h"

#include "gls/Numeric.h"

#include <algorithm>
#include <limits>

namespace gls
{
namespace
{

bool finitePosition(const double* p)
{
  return isFinite(p[0]) && isFinite(p[1]) && isFinite(p[2]);
}

/// A box being cut: its bounds and the sample points in it.
struct Piece
{
  double low[3], high[3];
  std::vector<const double*> sample;
  bool splittable = true;
  long parentCut = -1; ///< the cut whose child this box is (-1: the root)
  bool above = false;  ///< which child of it
  int depth = 0;
};

/// Halves `piece` at the median of its sample along the sample's longest extent into itself and `upper`; false (and
/// nothing changed) when the sample is one position or the median leaves one side empty.
bool halve(Piece& piece, Piece& upper, int& axisOut, double& splitOut)
{
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = hi[a] = piece.sample.front()[a];
  }
  for (const double* p : piece.sample)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  }
  int axis = 0;
  for (int a = 1; a < 3; ++a)
  {
    axis = hi[a] - lo[a] > hi[axis] - lo[axis] ? a : axis;
  }
  if (!(hi[axis] > lo[axis]))
  {
    return false;
  }
  std::vector<double> values;
  values.reserve(piece.sample.size());
  for (const double* p : piece.sample)
  {
    values.push_back(p[axis]);
  }
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  double split = *middle;
  if (!(split > lo[axis]))
  {
    // Half the sample or more at the lowest value: cut just above it instead.
    split = hi[axis];
    for (double v : values)
    {
      split = v > lo[axis] ? std::min(split, v) : split;
    }
  }
  axisOut = axis;
  splitOut = split;
  upper = Piece();
  std::copy(piece.low, piece.low + 3, upper.low);
  std::copy(piece.high, piece.high + 3, upper.high);
  upper.low[axis] = split;
  piece.high[axis] = split;
  std::vector<const double*> below;
  for (const double* p : piece.sample)
  {
    (p[axis] < split ? below : upper.sample).push_back(p);
  }
  piece.sample.swap(below);
  return true;
}

} // namespace

SpatialTiles SpatialTiles::plan(const double* xyz, std::size_t count, std::size_t tiles)
{
  const double inf = std::numeric_limits<double>::infinity();
  SpatialTiles result;
  std::vector<Piece> pieces(1);
  for (int a = 0; a < 3; ++a)
  {
    pieces[0].low[a] = -inf;
    pieces[0].high[a] = inf;
  }
  const std::size_t stride = std::max<std::size_t>(1, (count + kSample - 1) / kSample);
  for (std::size_t i = 0; i < count; i += stride)
  {
    if (finitePosition(xyz + 3 * i))
    {
      pieces[0].sample.push_back(xyz + 3 * i);
    }
  }
  while (pieces.size() < tiles)
  {
    // The splittable piece with the most sample points (the first of equals).
    std::size_t largest = pieces.size();
    for (std::size_t k = 0; k < pieces.size(); ++k)
    {
      const bool candidate =
        pieces[k].splittable && pieces[k].sample.size() >= 2 && pieces[k].depth < kMaximumDepth;
      if (candidate && (largest == pieces.size() || pieces[k].sample.size() > pieces[largest].sample.size()))
      {
        largest = k;
      }
    }
    if (largest == pieces.size())
    {
      break;
    }
    Piece upper;
    int axis = 0;
    double split = 0.0;
    if (halve(pieces[largest], upper, axis, split))
    {
      // The box's place in the cuts becomes a cut whose children are it and the new box.
      const long cut = static_cast<long>(result.Cuts.size());
      Piece& lower = pieces[largest];
      if (lower.parentCut >= 0)
      {
        Cut& parent = result.Cuts[static_cast<std::size_t>(lower.parentCut)];
        (lower.above ? parent.above : parent.below) = cut;
      }
      result.Cuts.push_back({ axis, split, -static_cast<long>(largest) - 1, -static_cast<long>(pieces.size()) - 1 });
      lower.parentCut = upper.parentCut = cut;
      lower.above = false;
      upper.above = true;
      lower.depth = upper.depth = lower.depth + 1;
      pieces.push_back(std::move(upper));
    }
    else
    {
      pieces[largest].splittable = false;
    }
  }
  for (const Piece& piece : pieces)
  {
    result.Low.push_back({ { piece.low[0], piece.low[1], piece.low[2] } });
    result.High.push_back({ { piece.high[0], piece.high[1], piece.high[2] } });
  }
  return result;
}

bool SpatialTiles::holds(std::size_t k, const double* p) const
{
  if (!finitePosition(p))
  {
    return k == 0;
  }
  for (int a = 0; a < 3; ++a)
  {
    if (!(p[a] >= this->Low[k].v[a] && p[a] < this->High[k].v[a]))
    {
      return false;
    }
  }
  return true;
}

std::size_t SpatialTiles::tileOf(const double* p) const
{
  if (this->Cuts.empty() || !finitePosition(p))
  {
    return 0;
  }
  long node = 0;
  while (node >= 0)
  {
    const Cut& c = this->Cuts[static_cast<std::size_t>(node)];
    node = p[c.axis] < c.split ? c.below : c.above;
  }
  return static_cast<std::size_t>(-node - 1);
}

bool SpatialTiles::near(std::size_t k, const double* p, double reach) const
{
  for (int a = 0; a < 3; ++a)
  {
    if (!(p[a] >= this->Low[k].v[a] - reach && p[a] <= this->High[k].v[a] + reach))
    {
      return false;
    }
  }
  return true;
}

} // namespace gls
