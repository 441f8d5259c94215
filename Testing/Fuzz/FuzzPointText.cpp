// libFuzzer target: the text point-cloud parser on arbitrary bytes. Invariants: no crash, no sanitizer report; on
// success whole points, a layout, and normals, colours, intensity and every other column either absent or one per
// point; on failure an error with a line number and nothing else.
#include "gls/PointTextParser.h"

#include <cstdint>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const gls::PointText t = gls::parsePointText(reinterpret_cast<const char*>(data), size);
  const std::size_t n = t.points.size() / 3;
  const auto absentOrPerPoint = [n](std::size_t count, std::size_t components) {
    return count == 0 || count == n * components;
  };
  if (t.error.empty())
  {
    bool ok = n > 0 && t.points.size() % 3 == 0 && !t.layout.empty() && absentOrPerPoint(t.normals.size(), 3) &&
      absentOrPerPoint(t.colors.size(), 3) && absentOrPerPoint(t.intensity.size(), 1);
    for (const gls::PointTextColumn& c : t.otherColumns)
    {
      ok = ok && c.values.size() == n;
    }
    if (!ok)
    {
      std::abort();
    }
  }
  else if (t.error.rfind("line ", 0) != 0 || !t.points.empty() || !t.normals.empty() || !t.colors.empty() ||
    !t.intensity.empty() || !t.otherColumns.empty() || !t.warning.empty())
  {
    std::abort();
  }
  return 0;
}
