// What a text file holds, told from its first bytes whatever its extension: a PCD or PTX file, or point text, and
// whether that point text reads as a point cloud (ParaView's reader factory asks this of .csv and .txt files).
#include "gls/PointTextParser.h"

#include "PointTextLayout.h"
#include "PointTextTable.h"
#include "TextCloudFormat.h"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <string_view>
#include <vector>

namespace gls
{
namespace
{

/// The blank-separated words of the text's first `maxLines` lines that are not blank (and, with `skipComments`, do
/// not start with '#'), one list per line.
std::vector<std::vector<std::string_view>> firstLinesWords(
  const char* text, std::size_t size, std::size_t maxLines, bool skipComments)
{
  std::vector<std::vector<std::string_view>> lines;
  const char* p = text;
  const char* end = text + size;
  while (p < end && lines.size() < maxLines)
  {
    const char* eol = std::find(p, end, '\n');
    std::vector<std::string_view> words = pointtext::blankSeparatedFields(p, eol);
    p = eol < end ? eol + 1 : end;
    if (!words.empty() && !(skipComments && words[0].substr(0, 1) == "#"))
    {
      lines.push_back(std::move(words));
    }
  }
  return lines;
}

bool isNumber(std::string_view word)
{
  double value = 0;
  const auto result = std::from_chars(word.data(), word.data() + word.size(), value);
  return result.ec == std::errc() && result.ptr == word.data() + word.size();
}

bool isCount(std::string_view word)
{
  return !word.empty() && std::all_of(word.begin(), word.end(), [](char c) { return c >= '0' && c <= '9'; });
}

bool isPcdHeader(const char* head, std::size_t size)
{
  const auto lines = firstLinesWords(head, size, 1, true);
  return !lines.empty() && (lines[0][0] == "VERSION" || lines[0][0] == "FIELDS");
}

bool isPtxHeader(const char* head, std::size_t size)
{
  static constexpr std::size_t widths[10] = { 1, 1, 3, 3, 3, 3, 4, 4, 4, 4 };
  const auto lines = firstLinesWords(head, size, 10, false);
  if (lines.size() < 10 || !isCount(lines[0][0]) || !isCount(lines[1][0]))
  {
    return false;
  }
  for (std::size_t k = 0; k < 10; ++k)
  {
    if (lines[k].size() != widths[k] || !std::all_of(lines[k].begin(), lines[k].end(), isNumber))
    {
      return false;
    }
  }
  return true;
}

} // namespace

TextCloudFormat textCloudFormat(const char* head, std::size_t size)
{
  if (isPcdHeader(head, size))
  {
    return TextCloudFormat::Pcd;
  }
  return isPtxHeader(head, size) ? TextCloudFormat::Ptx : TextCloudFormat::PointText;
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
