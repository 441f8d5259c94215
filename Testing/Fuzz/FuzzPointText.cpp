// libFuzzer target: the text point-cloud parser on arbitrary bytes. Invariants: no crash, no sanitizer report; on
// success whole points, a layout, and normals, colours, intensity and every other column either absent or one per
// point; on failure an error with a line number and nothing else. The judgement ParaView's reader factory asks of a
// file's first bytes (gls::pointCloudHeadError) agrees with the parser on a whole text, and never crashes on a part.
#include "gls/PointTextParser.h"

#include <cstdint>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const char* text = reinterpret_cast<const char*>(data);
  const gls::PointText t = gls::parsePointText(text, size);
  const std::string wholeHead = gls::pointCloudHeadError(text, size, true);
  const bool otherFormat = gls::textCloudFormat(text, size) != gls::TextCloudFormat::PointText;
  if (!otherFormat && wholeHead != t.error)
  {
    std::abort();
  }
  gls::pointCloudHeadError(text, size, false);
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
