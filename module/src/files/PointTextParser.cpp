#include "gls/PointTextParser.h"

#include "gls/FileContent.h"

#include "PointTextLayout.h"
#include "PointTextTable.h"
#include "TextCloudFormat.h"

#include <algorithm>
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

/// parse(bytes, size) of the file's whole content, its error and warning prefixed with the path (file content in
/// them made printable); an error naming the path when the file cannot be opened, and one naming what the file is
/// when its content is no text (`expected`: what the parser reads, e.g. "a text point cloud") and it has no PCD
/// header (a binary PCD's data follow its text header).
PointText parseFile(const std::string& path, PointText (*parse)(const char*, std::size_t), const char* expected)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    PointText failed;
    failed.error = path + ": cannot be opened (missing or not readable)";
    return failed;
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string bytes = buffer.str();
  const std::size_t head = std::min(bytes.size(), pointCloudHeadBytes);
  const std::string kind =
    textCloudFormat(bytes.data(), head) == TextCloudFormat::Pcd ? "" : binaryContentKind(bytes.data(), head);
  if (!kind.empty())
  {
    PointText failed;
    const auto dot = path.find_last_of("./");
    const std::string ext = dot != std::string::npos && path[dot] == '.' ? path.substr(dot) : "no extension";
    failed.error = path + ": " + kind + " by its content (named " + ext + "), not " + expected +
      (kind == "a LAS file" || kind == "a LAZ file" ? ": open it as .las (.laz)"
        : kind == "a PLY file" ? ": open it as .ply" : "");
    return failed;
  }
  PointText out = parse(bytes.data(), bytes.size());
  if (!out.error.empty())
  {
    out.error = path + ": " + printableText(out.error);
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
  return parseFile(path, pointtext::parseTextCloud, "a text point cloud");
}

PointText readPtxFile(const std::string& path)
{
  return parseFile(path, parsePtx, "a PTX scan");
}

PointText readPcdFile(const std::string& path)
{
  return parseFile(path, parsePcd, "a PCD file");
}

} // namespace gls
