// The first stage of the text point-cloud parser: text to a table of numbers (rows of equal width), with the header
// names if the file has a header line, checked point-count lines, and the line of every row. The rules (comments,
// separators, decimal commas, count lines) are documented in gls/PointTextParser.h.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace gls
{
namespace pointtext
{

struct Table
{
  std::vector<std::string> names;  ///< header names as written (empty without a header line)
  std::size_t headerLine = 0;      ///< the header's line number (0 without a header line)
  std::size_t width = 0;           ///< fields per row (0 when there are no rows)
  std::vector<double> values;      ///< row-major, width per row
  std::vector<std::size_t> lines;  ///< the line number (from 1) of each row
  std::size_t countLines = 0;      ///< point-count lines seen (each checked against the rows after it)
  std::string separators;          ///< how the data lines were split, e.g. "';', with decimal commas allowed"
  bool decimalCommas = false;      ///< whether a number of a data row was written with a decimal comma

  std::size_t rows() const { return lines.size(); }
  double at(std::size_t row, std::size_t column) const { return values[row * width + column]; }
};

/// The blank-separated fields of the text [begin, end) (quotes around a field removed), as the parser splits a line of
/// blank-separated data.
std::vector<std::string_view> blankSeparatedFields(const char* begin, const char* end);

/// Reads `size` bytes into `table`; returns "" or "line N: what is wrong". With `wholeText` false the text is a file's
/// first lines (its last point-count group may then hold fewer points than its count line says: the rest follows).
std::string readTable(const char* text, std::size_t size, Table& table, bool wholeText = true);

} // namespace pointtext
} // namespace gls
