#include "gls/ScaleSampling.h"

#include "gls/PointScaleSpace.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace gls
{

std::vector<double> sampleScales(double minScale, double maxScale, int count, ScaleSampling sampling)
{
  std::vector<double> t(static_cast<std::size_t>(count > 0 ? count : 0));
  for (int k = 0; k < count; ++k)
  {
    const double u = count > 1 ? static_cast<double>(k) / static_cast<double>(count - 1) : 0.0;
    switch (sampling)
    {
      case ScaleSampling::Linear:
        t[k] = minScale + (maxScale - minScale) * u;
        break;
      case ScaleSampling::Quadratic:
        t[k] = minScale + (maxScale - minScale) * u * u;
        break;
      case ScaleSampling::Logarithmic:
        t[k] = minScale * std::pow(maxScale / minScale, u);
        break;
    }
  }
  if (count > 1)
  {
    t[count - 1] = maxScale; // exact end point whatever the rounding of the formula
  }
  return t;
}

std::string checkScaleRange(double minScale, double maxScale, int count)
{
  std::ostringstream why;
  if (count < 1)
  {
    why << "NumberOfScales must be at least 1 (got " << count << ")";
  }
  else if (!std::isfinite(minScale) || !(minScale > 0.0))
  {
    why << "MinScale must be a finite positive length (got " << minScale << ")";
  }
  else if (!std::isfinite(maxScale) || maxScale < minScale)
  {
    why << "MaxScale must be finite and at least MinScale (got MinScale " << minScale << ", MaxScale " << maxScale
        << ")";
  }
  else if (count > 1 && !(maxScale > minScale))
  {
    why << "MaxScale must exceed MinScale when NumberOfScales > 1 (both are " << minScale << ")";
  }
  return why.str();
}

std::string checkScaleList(const std::vector<double>& scales)
{
  std::ostringstream why;
  if (scales.empty())
  {
    why << "the scale list is empty";
    return why.str();
  }
  for (std::size_t k = 0; k < scales.size(); ++k)
  {
    if (!std::isfinite(scales[k]) || !(scales[k] > 0.0))
    {
      why << "scale " << k << " is not a finite positive length (" << scales[k] << ")";
      return why.str();
    }
    if (k > 0 && !(scales[k] > scales[k - 1]))
    {
      why << "scales must be strictly increasing (scale " << k - 1 << " = " << scales[k - 1] << ", scale " << k
          << " = " << scales[k] << ")";
      return why.str();
    }
  }
  return why.str();
}

BinningTable makeBinningTable(const std::vector<double>& squaredScales)
{
  BinningTable t;
  const int S = static_cast<int>(squaredScales.size());
  if (S == 0)
  {
    return t;
  }
  const double top = squaredScales.back();
  double gap = squaredScales.front();
  for (int k = 1; k < S; ++k)
  {
    gap = std::min(gap, squaredScales[k] - squaredScales[k - 1]);
  }
  const double wanted = gap > 0.0 ? std::ceil(top / gap) + 1.0 : static_cast<double>(kMaxBinningCells);
  const int size = static_cast<int>(std::min(static_cast<double>(kMaxBinningCells), std::max(1024.0, wanted)));
  t.inverseCellWidth = size / top;
  t.cells.assign(static_cast<std::size_t>(size), BinningCell{ std::numeric_limits<double>::infinity(), 0, 0 });
  // The cell of each squared scale, computed as the lookup computes the cell of a squared distance.
  std::vector<int> holding(static_cast<std::size_t>(size), 0);
  for (int k = 0; k < S; ++k)
  {
    const double u = squaredScales[k] * t.inverseCellWidth;
    if (u >= 0.0 && u < static_cast<double>(size))
    {
      const int j = static_cast<int>(u);
      ++holding[j];
      t.cells[j].edge = squaredScales[k];
    }
  }
  int before = 0;
  for (int j = 0; j < size; ++j)
  {
    t.cells[j].base = holding[j] > 1 ? -1 : before;
    before += holding[j];
  }
  return t;
}

} // namespace gls
