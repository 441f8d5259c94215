#include "PointTextTable.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>

namespace gls
{
namespace pointtext
{
namespace
{

/// How the fields of a line are separated (gls/PointTextParser.h); Header: any of blanks, ',' and ';'.
enum class Split
{
  Header,
  Blanks,
  Commas,
  Semicolons
};

bool isBlank(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

bool isDigit(char c)
{
  return c >= '0' && c <= '9';
}

bool isDecimalComma(const char* comma, const char* begin, const char* end)
{
  return comma > begin && comma + 1 < end && isDigit(comma[-1]) && isDigit(comma[1]);
}

struct Field
{
  const char* begin;
  const char* end;
};

std::size_t countBlankSeparated(const char* begin, const char* end)
{
  std::size_t count = 0;
  for (const char* p = begin; p < end;)
  {
    while (p < end && isBlank(*p))
    {
      ++p;
    }
    if (p < end)
    {
      ++count;
    }
    while (p < end && !isBlank(*p))
    {
      ++p;
    }
  }
  return count;
}

/// The separators of a first data line.
Split detectSplit(const char* begin, const char* end)
{
  if (std::find(begin, end, ';') != end)
  {
    return Split::Semicolons;
  }
  bool anyComma = false, allDecimal = true;
  for (const char* p = begin; p < end; ++p)
  {
    if (*p == ',')
    {
      anyComma = true;
      allDecimal = allDecimal && isDecimalComma(p, begin, end);
    }
  }
  if (!anyComma || (allDecimal && countBlankSeparated(begin, end) >= 2))
  {
    return Split::Blanks;
  }
  return Split::Commas;
}

Field trimmed(const char* begin, const char* end)
{
  while (begin < end && isBlank(*begin))
  {
    ++begin;
  }
  while (end > begin && isBlank(end[-1]))
  {
    --end;
  }
  if (end - begin >= 2 && *begin == '"' && end[-1] == '"')
  {
    ++begin;
    --end;
  }
  return { begin, end };
}

/// Blanks and headers: runs of separators between fields. Commas and semicolons: one delimiter between fields
/// (an empty field stays, to be reported), a trailing delimiter is ignored.
void splitFields(Split split, const char* begin, const char* end, std::vector<Field>& fields)
{
  fields.clear();
  if (split == Split::Commas || split == Split::Semicolons)
  {
    const char delimiter = split == Split::Commas ? ',' : ';';
    for (const char* p = begin;;)
    {
      const char* stop = std::find(p, end, delimiter);
      const Field f = trimmed(p, stop);
      if (stop < end || f.end > f.begin)
      {
        fields.push_back(f);
      }
      if (stop == end)
      {
        return;
      }
      p = stop + 1;
    }
  }
  const auto separates = [split](char c) { return isBlank(c) || (split == Split::Header && (c == ',' || c == ';')); };
  for (const char* p = begin; p < end;)
  {
    while (p < end && separates(*p))
    {
      ++p;
    }
    const char* start = p;
    while (p < end && !separates(*p))
    {
      ++p;
    }
    if (p > start)
    {
      fields.push_back(trimmed(start, p));
    }
  }
}

/// A whole field as a number; with decimalComma, one comma between two digits reads as the decimal point.
bool parseNumber(Field f, bool decimalComma, double& value, bool& usedComma)
{
  const char* first = f.begin;
  const char* last = f.end;
  if (first < last && *first == '+')
  {
    ++first;
    if (first < last && (*first == '-' || *first == '+'))
    {
      return false;
    }
  }
  char buffer[128];
  const char* comma = decimalComma ? std::find(first, last, ',') : last;
  if (comma != last)
  {
    if (!isDecimalComma(comma, first, last) || last - first >= static_cast<std::ptrdiff_t>(sizeof buffer))
    {
      return false;
    }
    const std::size_t n = static_cast<std::size_t>(last - first);
    std::memcpy(buffer, first, n);
    buffer[comma - first] = '.';
    usedComma = true;
    first = buffer;
    last = buffer + n;
  }
  const auto result = std::from_chars(first, last, value);
  return result.ec == std::errc() && result.ptr == last && first < last;
}

/// A header field starts with a letter or '_' (a field such as "1,5,5" or "" is a malformed number instead).
bool startsWithName(Field f)
{
  return f.begin < f.end && (std::isalpha(static_cast<unsigned char>(*f.begin)) || *f.begin == '_');
}

bool isCloudCompareHeader(const char* begin, const char* end)
{
  return end - begin >= 2 && begin[0] == '/' && begin[1] == '/';
}

bool isPointCount(double value)
{
  return value >= 0 && value < 9007199254740992.0 && std::floor(value) == value;
}

std::string describe(Split split)
{
  switch (split)
  {
    case Split::Commas:
      return "','";
    case Split::Semicolons:
      return "';', with decimal commas allowed";
    default:
      return "blanks, with decimal commas allowed";
  }
}

std::string pointCountMismatch(std::size_t declared, std::size_t found)
{
  return "the point count line says " + std::to_string(declared) + " point" + (declared == 1 ? "" : "s") +
    ", but " + std::to_string(found) + " follow" + (found == 1 ? "s" : "");
}

} // namespace

std::vector<std::string_view> blankSeparatedFields(const char* begin, const char* end)
{
  std::vector<Field> fields;
  splitFields(Split::Blanks, begin, end, fields);
  std::vector<std::string_view> out;
  out.reserve(fields.size());
  for (const Field& f : fields)
  {
    out.emplace_back(f.begin, static_cast<std::size_t>(f.end - f.begin));
  }
  return out;
}

std::string readTable(const char* text, std::size_t size, Table& table, bool wholeText)
{
  table = Table();
  const char* p = text;
  const char* end = text + size;
  if (size >= 3 && std::memcmp(p, "\xEF\xBB\xBF", 3) == 0)
  {
    p += 3;
  }
  bool splitKnown = false;
  Split split = Split::Blanks;
  std::vector<Field> fields;
  std::vector<double> row;
  std::size_t lineNumber = 0, countLine = 0, declared = 0, rowsBeforeCount = 0;
  const auto fail = [&](std::size_t line, const std::string& what) {
    table = Table();
    return "line " + std::to_string(line) + ": " + what;
  };
  const auto countHolds = [&]() { return countLine == 0 || table.rows() - rowsBeforeCount == declared; };
  while (p < end)
  {
    const char* eol = std::find(p, end, '\n');
    const char* stop = std::find(p, eol, '#');
    const char* begin = p;
    ++lineNumber;
    p = eol < end ? eol + 1 : end;
    while (begin < stop && isBlank(*begin))
    {
      ++begin;
    }
    if (begin == stop)
    {
      continue;
    }
    const Split lineSplit = splitKnown ? split : detectSplit(begin, stop);
    splitFields(lineSplit, begin, stop, fields);
    row.resize(fields.size());
    std::size_t bad = fields.size();
    bool usedComma = false;
    for (std::size_t i = 0; i < fields.size() && bad == fields.size(); ++i)
    {
      if (!parseNumber(fields[i], lineSplit != Split::Commas, row[i], usedComma))
      {
        bad = i;
      }
    }
    if (bad < fields.size())
    {
      const bool named = std::any_of(fields.begin(), fields.end(), startsWithName);
      if (table.rows() == 0 && table.names.empty() && (named || isCloudCompareHeader(begin, stop)))
      {
        if (isCloudCompareHeader(begin, stop))
        {
          begin += 2; // CloudCompare writes its header line as //X,Y,Z,...
        }
        splitFields(Split::Header, begin, stop, fields);
        for (const Field& f : fields)
        {
          table.names.emplace_back(f.begin, f.end);
        }
        table.width = table.names.size();
        table.headerLine = lineNumber;
        continue;
      }
      const std::string field(fields[bad].begin, fields[bad].end);
      return fail(lineNumber,
        (field.empty() ? "empty field in column " + std::to_string(bad + 1)
                       : "not a number in column " + std::to_string(bad + 1) + ": '" + field + "'") +
          (splitKnown ? "; this file's fields are separated by " + table.separators : ""));
    }
    if (fields.size() == 1 && isPointCount(row[0]))
    {
      if (!countHolds())
      {
        return fail(countLine, pointCountMismatch(declared, table.rows() - rowsBeforeCount));
      }
      countLine = lineNumber;
      declared = static_cast<std::size_t>(row[0]);
      rowsBeforeCount = table.rows();
      ++table.countLines;
      continue;
    }
    if (!splitKnown)
    {
      splitKnown = true;
      split = lineSplit;
      table.separators = describe(split);
    }
    if (table.width == 0)
    {
      table.width = fields.size();
    }
    if (fields.size() != table.width)
    {
      return fail(lineNumber, "expected " + std::to_string(table.width) + " columns " +
          (table.rows() == 0 ? "as the header line names" : "like the lines before") + ", got " +
          std::to_string(fields.size()));
    }
    table.decimalCommas = table.decimalCommas || usedComma;
    table.values.insert(table.values.end(), row.begin(), row.end());
    table.lines.push_back(lineNumber);
  }
  if (!countHolds() && (wholeText || table.rows() - rowsBeforeCount > declared))
  {
    return fail(countLine, pointCountMismatch(declared, table.rows() - rowsBeforeCount));
  }
  if (table.rows() == 0)
  {
    return fail(lineNumber, "no points found");
  }
  return {};
}

} // namespace pointtext
} // namespace gls
