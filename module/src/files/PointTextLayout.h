// The second stage of the text point-cloud parser: what each column of the table means, from the header names or,
// without a header, from the number of columns and their values (the rules are in gls/PointTextParser.h).
#pragma once

#include "PointTextTable.h"

#include <string>
#include <vector>

namespace gls
{
namespace pointtext
{

struct Layout
{
  int xyz[3] = { -1, -1, -1 };
  int normals[3] = { -1, -1, -1 }; ///< -1: none
  int colors[3] = { -1, -1, -1 };  ///< -1: none
  bool colorFractions = false;     ///< colours given as 0-1 fractions (else 0-255 integers)
  int intensity = -1;              ///< -1: none
  std::vector<int> others;         ///< columns kept under their header names
  std::string description;         ///< e.g. "x y z r g b (6 columns, no header: 0-255 integers, so colours)"
};

/// Chooses the layout of `table`; returns "" or "line N: what is wrong".
std::string chooseLayout(const Table& table, Layout& layout);

} // namespace pointtext
} // namespace gls
