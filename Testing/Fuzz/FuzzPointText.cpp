// libFuzzer target: the text point-cloud parser on arbitrary bytes. Invariants: no crash, no sanitizer report; on
// success whole points, and normals either absent or one per point; on failure an error with a line number.
#include "gls/PointTextParser.h"

#include <cstdint>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const gls::PointText t = gls::parsePointText(reinterpret_cast<const char*>(data), size);
  if (t.error.empty())
  {
    if (t.points.empty() || t.points.size() % 3 != 0 || (!t.normals.empty() && t.normals.size() != t.points.size()))
    {
      std::abort();
    }
  }
  else if (t.error.rfind("line ", 0) != 0 || !t.points.empty())
  {
    std::abort();
  }
  return 0;
}
