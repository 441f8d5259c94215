// What a text file holds, told from its first bytes whatever its extension: a PCD or PTX file, or point text, and
// whether that point text reads as a point cloud (ParaView's reader factory asks this of .csv and .txt files).
#include "gls/PointTextParser.h"

#include "PointTextLayout.h"
#include "PointTextTable.h"
#include "TextCloudFormat.h"

#include <algorithm>
#include <fstream>
#include <string_view>
#include <vector>

namespace gls
{
namespace
{

/// A PCL PCD header: the first line that is not blank or a '#' comment starts with VERSION or FIELDS.
bool isPcdHeader(const char* text, std::size_t size)
{
  const char* p = text;
  const char* end = text + size;
  while (p < end)
  {
    const char* eol = std::find(p, end, '\n');
    const std::vector<std::string_view> words = pointtext::blankSeparatedFields(p, eol);
    p = eol < end ? eol + 1 : end;
    if (!words.empty() && words[0].substr(0, 1) != "#")
    {
      return words[0] == "VERSION" || words[0] == "FIELDS";
    }
  }
  return false;
}

} // namespace

TextCloudFormat textCloudFormat(const char* head, std::size_t size)
{
  if (isPcdHeader(head, size))
  {
    return TextCloudFormat::Pcd;
  }
  return pointtext::beginsWithPtxHeader(head, size) ? TextCloudFormat::Ptx : TextCloudFormat::PointText;
}

std::string pointCloudHeadError(const char* head, std::size_t size, bool wholeFile)
{
  if (textCloudFormat(head, size) != TextCloudFormat::PointText)
  {
    return {};
  }
  if (!wholeFile)
  {
    const char* lastNewline = std::find(std::reverse_iterator<const char*>(head + size),
                                  std::reverse_iterator<const char*>(head), '\n')
                                .base();
    if (lastNewline == head)
    {
      return "no line ends in the first " + std::to_string(size) + " bytes";
    }
    size = static_cast<std::size_t>(lastNewline - head);
  }
  pointtext::Table table;
  std::string error = pointtext::readTable(head, size, table, wholeFile);
  if (error.empty())
  {
    pointtext::Layout layout;
    error = pointtext::chooseLayout(table, layout);
  }
  return error;
}

std::string pointCloudFileHeadError(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    return path + ": cannot be opened (missing or not readable)";
  }
  std::string head(pointCloudHeadBytes, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  const bool wholeFile = in.peek() == std::ifstream::traits_type::eof();
  const std::string error = pointCloudHeadError(head.data(), head.size(), wholeFile);
  return error.empty() ? error : path + ": " + error;
}

namespace pointtext
{

PointText parseTextCloud(const char* text, std::size_t size)
{
  const TextCloudFormat format = textCloudFormat(text, size);
  if (format == TextCloudFormat::PointText)
  {
    return parsePointText(text, size);
  }
  const bool pcd = format == TextCloudFormat::Pcd;
  PointText out = pcd ? parsePcd(text, size) : parsePtx(text, size);
  const std::string what = pcd ? "a PCL PCD file by its content" : "a Leica PTX file by its content";
  (out.error.empty() ? out.layout : out.error) = what + ": " + (out.error.empty() ? out.layout : out.error);
  return out;
}

} // namespace pointtext

} // namespace gls
