#include "gls/PlyWriter.h"

#include "gls/Numeric.h"

#include "LittleEndian.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace gls
{
namespace
{

/// The property names of a scalar source, one per component.
std::vector<std::string> namesOf(const PlyScalarSource& s)
{
  std::vector<std::string> names;
  for (int c = 0; c < s.components; ++c)
  {
    std::string suffix = s.components == 3 ? std::string("_") + "xyz"[c]
      : s.components > 1                   ? "_" + std::to_string(c)
                                           : "";
    names.push_back("scalar_" + plyPropertyName(s.name) + suffix);
  }
  return names;
}

} // namespace

std::string plyPropertyName(const std::string& name)
{
  std::string out = name.empty() ? std::string("unnamed") : name;
  for (char& c : out)
  {
    const unsigned char u = static_cast<unsigned char>(c);
    c = u <= 0x20 || u >= 0x7f ? '_' : c;
  }
  return out;
}

bool writePly(std::ostream& out, const PlyWriteSource& s, PlyWriteResult& result, std::string& error)
{
  result = PlyWriteResult();
  // The points written and their new numbers (a left-out point: -1).
  std::vector<std::int64_t> number(s.n, -1);
  for (std::size_t i = 0; i < s.n; ++i)
  {
    if (isFinitePoint(s.xyz + 3 * i))
    {
      number[i] = static_cast<std::int64_t>(result.written++);
    }
  }
  result.leftOut = s.n - result.written;
  std::vector<std::size_t> faces;
  for (std::size_t f = 0; f + 1 < s.faceOffsets.size(); ++f)
  {
    bool kept = s.faceOffsets[f + 1] - s.faceOffsets[f] >= 3 && s.faceOffsets[f + 1] - s.faceOffsets[f] <= 255;
    for (std::int64_t k = s.faceOffsets[f]; kept && k < s.faceOffsets[f + 1]; ++k)
    {
      const std::int64_t id = s.faceIndices[static_cast<std::size_t>(k)];
      kept = id >= 0 && static_cast<std::size_t>(id) < s.n && number[static_cast<std::size_t>(id)] >= 0;
    }
    (kept ? result.faces : result.facesLeftOut) += 1;
    if (kept)
    {
      faces.push_back(f);
    }
  }
  std::ostringstream h;
  h << "ply\nformat binary_little_endian 1.0\n";
  for (const std::string& c : s.comments)
  {
    std::string line = c;
    std::replace(line.begin(), line.end(), '\n', ' ');
    h << "comment " << line << "\n";
  }
  h << "element vertex " << result.written << "\n";
  const char* position = s.floatPositions ? "float" : "double";
  h << "property " << position << " x\nproperty " << position << " y\nproperty " << position << " z\n";
  if (s.normals)
  {
    h << "property float nx\nproperty float ny\nproperty float nz\n";
  }
  if (s.colours)
  {
    h << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  }
  for (const PlyScalarSource& scalar : s.scalars)
  {
    for (const std::string& name : namesOf(scalar))
    {
      h << "property " << (scalar.doubles ? "double " : "float ") << name << "\n";
    }
  }
  if (!faces.empty())
  {
    h << "element face " << faces.size() << "\nproperty list uchar int vertex_indices\n";
  }
  h << "end_header\n";
  out << h.str();
  std::string block;
  for (std::size_t i = 0; i < s.n && out; ++i)
  {
    if (number[i] < 0)
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      s.floatPositions ? appendLittleEndian<float>(block, static_cast<float>(s.xyz[3 * i + a])) : appendLittleEndian<double>(block, s.xyz[3 * i + a]);
    }
    for (int a = 0; s.normals && a < 3; ++a)
    {
      appendLittleEndian<float>(block, s.normals[3 * i + a]);
    }
    for (int a = 0; s.colours && a < 3; ++a)
    {
      appendLittleEndian<std::uint8_t>(block, s.colours[3 * i + a]);
    }
    for (const PlyScalarSource& scalar : s.scalars)
    {
      for (int c = 0; c < scalar.components; ++c)
      {
        const std::size_t at = static_cast<std::size_t>(scalar.components) * i + static_cast<std::size_t>(c);
        scalar.floats ? appendLittleEndian<float>(block, scalar.floats[at])
                      : appendLittleEndian<double>(block, scalar.doubles[at]);
      }
    }
    if (block.size() >= (std::size_t(4) << 20))
    {
      out.write(block.data(), static_cast<std::streamsize>(block.size()));
      block.clear();
    }
  }
  for (std::size_t f : faces)
  {
    appendLittleEndian<std::uint8_t>(block, static_cast<std::uint8_t>(s.faceOffsets[f + 1] - s.faceOffsets[f]));
    for (std::int64_t k = s.faceOffsets[f]; k < s.faceOffsets[f + 1]; ++k)
    {
      appendLittleEndian<std::int32_t>(block, static_cast<std::int32_t>(number[static_cast<std::size_t>(s.faceIndices[k])]));
    }
    if (block.size() >= (std::size_t(4) << 20))
    {
      out.write(block.data(), static_cast<std::streamsize>(block.size()));
      block.clear();
    }
  }
  out.write(block.data(), static_cast<std::streamsize>(block.size()));
  if (!out)
  {
    error = "the file could not be written (a full disk?)";
    return false;
  }
  return true;
}

} // namespace gls
