// Binary PLY files (little endian) written from plain arrays: the points (float or double, as given), normals as
// nx ny nz, colours as red green blue, every other per-point value as a property named scalar_<name> (the name
// CloudCompare loads as a scalar field without asking), and faces. Points with a non-finite coordinate are left out
// (other tools' readers do not expect NaN positions), and the faces that use them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace gls
{

/// A per-point value written as properties `scalar_<name>` (a vector's as `scalar_<name>_x`, `_y`, `_z`, or `_0`...
/// for other counts), float from floats, double from doubles (exactly one of the two pointers is set).
struct PlyScalarSource
{
  std::string name; ///< blanks and characters PLY's header cannot hold are written as '_'
  int components = 1;
  const float* floats = nullptr;
  const double* doubles = nullptr;
};

struct PlyWriteSource
{
  std::size_t n = 0;
  const double* xyz = nullptr;            ///< 3 per point
  bool floatPositions = false;            ///< write x y z as float (the input's own type) instead of double
  const float* normals = nullptr;         ///< 3 per point, or null
  const std::uint8_t* colours = nullptr;  ///< 3 per point (0-255), or null
  std::vector<PlyScalarSource> scalars;
  /// Faces: faceOffsets (faces + 1 values) into faceIndices (point ids), or empty.
  std::vector<std::int64_t> faceOffsets, faceIndices;
  std::vector<std::string> comments;      ///< written as header comments (one line each)
};

struct PlyWriteResult
{
  std::uint64_t written = 0, leftOut = 0; ///< points written, and left out (a non-finite coordinate)
  std::uint64_t faces = 0, facesLeftOut = 0;
};

/// Writes the PLY file; false with `error` when the stream fails.
bool writePly(std::ostream& out, const PlyWriteSource& source, PlyWriteResult& result, std::string& error);

/// A PLY property name made of the characters a header word can hold (blanks and controls as '_').
std::string plyPropertyName(const std::string& name);

} // namespace gls
