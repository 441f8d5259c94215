#include "gls/PointTextParser.h"

#include "PointTextLayout.h"
#include "PointTextTable.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace gls
{
namespace
{

void copyColumns(const pointtext::Table& t, const int columns[3], std::vector<double>& out)
{
  out.resize(3 * t.rows());
  for (std::size_t row = 0; row < t.rows(); ++row)
  {
    for (int k = 0; k < 3; ++k)
    {
      out[3 * row + k] = t.at(row, columns[k]);
    }
  }
}

/// "K of N normals have a length far from 1 ...", or "" when every normal is unit length within the tolerance.
std::string normalLengthWarning(const pointtext::Table& t, const std::vector<double>& normals)
{
  std::size_t far = 0, firstRow = 0;
  double firstLength = 0;
  for (std::size_t row = 0; row < t.rows(); ++row)
  {
    const double length = std::hypot(normals[3 * row], normals[3 * row + 1], normals[3 * row + 2]);
    if (!(std::abs(length - 1) <= unitLengthTolerance))
    {
      if (far++ == 0)
      {
        firstRow = row;
        firstLength = length;
      }
    }
  }
  if (far == 0)
  {
    return {};
  }
  std::ostringstream s;
  s << far << " of " << t.rows() << " normals have a length far from 1 (|length - 1| > " << unitLengthTolerance
    << "; the first at line " << t.lines[firstRow] << ": " << firstLength
    << "); the GLS filters use their directions and leave zero or non-finite ones out";
  return s.str();
}

} // namespace

PointText parsePointText(const char* text, std::size_t size)
{
  PointText out;
  pointtext::Table table;
  pointtext::Layout layout;
  out.error = pointtext::readTable(text, size, table);
  if (out.error.empty())
  {
    out.error = pointtext::chooseLayout(table, layout);
  }
  if (!out.error.empty())
  {
    return out;
  }
  const std::size_t n = table.rows();
  copyColumns(table, layout.xyz, out.points);
  if (layout.normals[0] >= 0)
  {
    copyColumns(table, layout.normals, out.normals);
    out.warning = normalLengthWarning(table, out.normals);
  }
  if (layout.colors[0] >= 0)
  {
    std::vector<double> colors;
    copyColumns(table, layout.colors, colors);
    out.colors.resize(colors.size());
    for (std::size_t i = 0; i < colors.size(); ++i)
    {
      out.colors[i] = static_cast<unsigned char>(layout.colorFractions ? std::lround(255 * colors[i]) : colors[i]);
    }
  }
  if (layout.intensity >= 0)
  {
    out.intensity.resize(n);
    for (std::size_t row = 0; row < n; ++row)
    {
      out.intensity[row] = static_cast<float>(table.at(row, layout.intensity));
    }
  }
  for (const int c : layout.others)
  {
    PointTextColumn column{ table.names[c], std::vector<double>(n) };
    for (std::size_t row = 0; row < n; ++row)
    {
      column.values[row] = table.at(row, c);
    }
    out.otherColumns.push_back(std::move(column));
  }
  out.layout = layout.description;
  if (table.countLines > 0)
  {
    out.layout += "; " + std::to_string(table.countLines) + " point count line" + (table.countLines > 1 ? "s" : "");
  }
  if (table.decimalCommas)
  {
    out.layout += "; decimal commas";
  }
  return out;
}

namespace
{

/// The file's text, or an error naming the path.
bool readWholeFile(const std::string& path, std::string& text, PointText& out)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    out.error = path + ": cannot be opened (missing or not readable)";
    return false;
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  text = buffer.str();
  return true;
}

PointText prefixed(PointText out, const std::string& path)
{
  if (!out.error.empty())
  {
    out.error = path + ": " + out.error;
  }
  if (!out.warning.empty())
  {
    out.warning = path + ": " + out.warning;
  }
  return out;
}

} // namespace

PointText readPointTextFile(const std::string& path)
{
  std::string text;
  PointText out;
  if (!readWholeFile(path, text, out))
  {
    return out;
  }
  return prefixed(parsePointText(text.data(), text.size()), path);
}

PointText readPtxFile(const std::string& path)
{
  std::string text;
  PointText out;
  if (!readWholeFile(path, text, out))
  {
    return out;
  }
  return prefixed(parsePtx(text.data(), text.size()), path);
}

PointText readPcdFile(const std::string& path)
{
  std::string bytes;
  PointText out;
  if (!readWholeFile(path, bytes, out))
  {
    return out;
  }
  return prefixed(parsePcd(bytes.data(), bytes.size()), path);
}

} // namespace gls
