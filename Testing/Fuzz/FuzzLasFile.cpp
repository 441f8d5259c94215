// libFuzzer target: the LAS reader (gls/LasFile.h) on arbitrary bytes. Invariants: no crash, no sanitizer report, no
// allocation beyond what the file can hold; a header is accepted only with its points inside the file; a refusal says
// why.
#include "gls/LasFile.h"

#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
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
  std::vector<std::vector<double>> extra(h.extra.size(), std::vector<double>(n));
  gls::LasColumns c;
  c.xyz = xyz.data();
  c.intensity = intensity.data();
  c.gpsTime = gps.data();
  c.rgb = rgb.data();
  c.nir = nir.data();
  for (auto& e : extra)
  {
    c.extra.push_back(e.data());
  }
  if (!gls::readLasPoints(in, h, c, error) && error.empty())
  {
    std::abort();
  }
  return 0;
}
