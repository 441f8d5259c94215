#include "gls/PointBox.h"

#include "gls/Numeric.h"

#include <algorithm>

namespace gls
{

PointBox boxOfFinitePoints(const double* xyz, std::size_t n, const unsigned char* include)
{
  PointBox box;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double* p = xyz + 3 * i;
    if ((include != nullptr && include[i] == 0) || !isFinite(p[0]) || !isFinite(p[1]) || !isFinite(p[2]))
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      box.low[a] = box.count == 0 ? p[a] : std::min(box.low[a], p[a]);
      box.high[a] = box.count == 0 ? p[a] : std::max(box.high[a], p[a]);
    }
    ++box.count;
  }
  return box;
}

} // namespace gls
