#include "gls/FileContent.h"

#include <cstdio>
#include <cstring>

namespace gls
{

namespace
{

bool startsWith(const char* head, std::size_t size, const char* prefix)
{
  const std::size_t n = std::strlen(prefix);
  return size >= n && std::memcmp(head, prefix, n) == 0;
}

} // namespace

std::string binaryContentKind(const char* head, std::size_t size)
{
  if (startsWith(head, size, "LASF"))
  {
    // The point format's two high bits mark LASzip's compressed records.
    return size > 104 && (static_cast<unsigned char>(head[104]) & 0xC0) != 0 ? "a LAZ file" : "a LAS file";
  }
  if (startsWith(head, size, "ply\n") || startsWith(head, size, "ply\r\n"))
  {
    return "a PLY file";
  }
  if (startsWith(head, size, "ASTM-E57"))
  {
    return "an E57 file";
  }
  if (startsWith(head, size, "<VTKFile") ||
    (startsWith(head, size, "<?xml") && std::string(head, size < 512 ? size : 512).find("<VTKFile") != std::string::npos))
  {
    return "a VTK XML file";
  }
  if (startsWith(head, size, "PK\x03\x04"))
  {
    return "a ZIP archive";
  }
  if (startsWith(head, size, "\x1f\x8b"))
  {
    return "a gzip archive";
  }
  std::size_t control = 0;
  for (std::size_t i = 0; i < size; ++i)
  {
    const unsigned char c = static_cast<unsigned char>(head[i]);
    if (c == 0)
    {
      return "a binary file";
    }
    control += c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\f' && c != '\v' ? 1 : 0;
  }
  return control * 100 > size ? "a binary file" : "";
}

std::string printableText(const std::string& text, std::size_t limit)
{
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i)
  {
    if (out.size() >= limit)
    {
      out += "...";
      break;
    }
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f)
    {
      out += static_cast<char>(c);
      continue;
    }
    char escaped[8];
    std::snprintf(escaped, sizeof(escaped), "\\x%02x", c);
    out += escaped;
  }
  return out;
}

} // namespace gls
