// libFuzzer target: the scanners' file readers on arbitrary bytes, each input given to all of them: LAS
// (gls/LasFile.h), PCD and PTX (gls/PointTextParser.h). Invariants: no crash, no sanitizer report, no allocation
// beyond what the file can hold; LAS: a header is accepted only with its points inside the file; PCD and PTX: on
// success whole points with per-point attributes, on failure an error and nothing else; a refusal always says why.
#include "gls/FileContent.h"
#include "gls/LasFile.h"
#include "gls/PointTextParser.h"

#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace
{

void checkCloud(const gls::PointText& t)
{
  const std::size_t n = t.points.size() / 3;
  const auto absentOrPerPoint = [n](std::size_t count, std::size_t components) {
    return count == 0 || count == n * components;
  };
  if (t.error.empty())
  {
    bool ok = t.points.size() % 3 == 0 && !t.layout.empty() && absentOrPerPoint(t.normals.size(), 3) &&
      absentOrPerPoint(t.colors.size(), 3) && absentOrPerPoint(t.intensity.size(), 1) &&
      absentOrPerPoint(t.viewpoints.size(), 3);
    for (const gls::PointTextColumn& c : t.otherColumns)
    {
      ok = ok && c.values.size() == n;
    }
    if (!ok)
    {
      std::abort();
    }
  }
  else if (!t.points.empty() || !t.normals.empty() || !t.colors.empty() || !t.viewpoints.empty())
  {
    std::abort();
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  checkCloud(gls::parsePcd(reinterpret_cast<const char*>(data), size));
  checkCloud(gls::parsePtx(reinterpret_cast<const char*>(data), size));
  gls::printableText(gls::binaryContentKind(reinterpret_cast<const char*>(data), size) +
    std::string(reinterpret_cast<const char*>(data), size < 64 ? size : 64));
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  std::istringstream in(bytes);
  gls::LasHeader h;
  std::string error;
  if (!gls::readLasHeader(in, size, h, error))
  {
    if (error.empty())
    {
      std::abort();
    }
    return 0;
  }
  if (h.recordLength < gls::lasFormatSize(h.format) || h.pointOffset > size ||
    h.pointCount > (size - h.pointOffset) / h.recordLength)
  {
    std::abort();
  }
  const std::size_t n = static_cast<std::size_t>(h.pointCount);
  std::vector<double> xyz(3 * n), gps(n);
  std::vector<std::uint16_t> intensity(n), rgb(3 * n), nir(n);
  std::vector<std::uint8_t> withheld(n), synthetic(n), keyPoint(n), overlap(n), direction(n), edge(n), channel(n);
  std::vector<std::vector<double>> extra;
  for (const gls::LasExtraBytes& x : h.extra)
  {
    if (x.components < 1 || x.components > 3)
    {
      std::abort();
    }
    extra.emplace_back(static_cast<std::size_t>(x.components) * n);
  }
  gls::LasColumns c;
  c.xyz = xyz.data();
  c.intensity = intensity.data();
  c.gpsTime = gps.data();
  c.rgb = rgb.data();
  c.nir = nir.data();
  c.withheld = withheld.data();
  c.synthetic = synthetic.data();
  c.keyPoint = keyPoint.data();
  c.overlap = overlap.data();
  c.scanDirection = direction.data();
  c.edgeOfFlightLine = edge.data();
  c.scannerChannel = channel.data();
  c.skipWithheld = size % 2 == 1; // both ways, from the input's parity
  for (auto& e : extra)
  {
    c.extra.push_back(e.data());
  }
  gls::LasReadResult read;
  const bool ok = gls::readLasPoints(in, h, c, read, error);
  if ((!ok && error.empty()) || read.written > n || read.withheld > n ||
    (ok && read.written + (c.skipWithheld ? read.withheld : 0) != n))
  {
    std::abort();
  }
  return 0;
}
