// Parser of text point clouds (XYZ, PTS, CSV): one point per line, fields separated by spaces, tabs, commas or
// semicolons; '#' starts a comment; blank lines are skipped. Columns: 3 (x y z) or 6 (x y z nx ny nz), or any number
// after a header line that names them (x, y, z and optionally nx, ny, nz, case-insensitive; other columns are
// ignored). Numbers are read locale-independently. Never throws; malformed input gives an error with its line.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace gls
{

struct PointText
{
  std::vector<double> points;  ///< 3 per point
  std::vector<double> normals; ///< 3 per point, or empty when the file has none
  std::string error;           ///< empty on success, else "line N: what is wrong"
};

/// Parses `size` bytes of text.
PointText parsePointText(const char* text, std::size_t size);

/// Reads and parses a file; error names the file when it cannot be read.
PointText readPointTextFile(const std::string& path);

} // namespace gls
