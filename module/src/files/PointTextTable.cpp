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

namespace
{

/// Reads a table line by line: the header line, point-count lines and data rows, each checked where it is read.
class TableReader
{
public:
  explicit TableReader(Table& table)
    : T(table)
  {
  }

  /// One line's content [begin, stop) (no comment, not blank), line number `line`; "" or the error.
  std::string read(const char* begin, const char* stop, std::size_t line)
  {
    this->Line = line;
    const Split lineSplit = this->SplitKnown ? this->LineSplit : detectSplit(begin, stop);
    splitFields(lineSplit, begin, stop, this->Fields);
    this->Row.resize(this->Fields.size());
    std::size_t bad = this->Fields.size();
    bool usedComma = false;
    for (std::size_t i = 0; i < this->Fields.size() && bad == this->Fields.size(); ++i)
    {
      if (!parseNumber(this->Fields[i], lineSplit != Split::Commas, this->Row[i], usedComma))
      {
        bad = i;
      }
    }
    if (bad < this->Fields.size())
    {
      return this->readHeader(begin, stop) ? "" : this->notANumber(bad);
    }
    if (this->Fields.size() == 1 && isPointCount(this->Row[0]))
    {
      return this->readCount();
    }
    return this->addRow(lineSplit, usedComma);
  }

  /// After the last line (`lines` lines in all, blank ones included): "" or the error (a point-count group short of
  /// its count, unless `wholeText` is false and the rest of the text may hold the rest; no points).
  std::string finish(bool wholeText, std::size_t lines) const
  {
    if (!this->countHolds() && (wholeText || this->T.rows() - this->RowsBeforeCount > this->Declared))
    {
      return fail(this->CountLine, pointCountMismatch(this->Declared, this->T.rows() - this->RowsBeforeCount));
    }
    return this->T.rows() == 0 ? fail(lines, "no points found") : "";
  }

  static std::string fail(std::size_t line, const std::string& what)
  {
    return "line " + std::to_string(line) + ": " + what;
  }

private:
  bool countHolds() const
  {
    return this->CountLine == 0 || this->T.rows() - this->RowsBeforeCount == this->Declared;
  }

  /// A line with a field that is no number, before any data and any other header: the header line, when it names
  /// its columns (or is CloudCompare's //X,Y,Z,...). Whether it was one.
  bool readHeader(const char* begin, const char* stop)
  {
    const bool named = std::any_of(this->Fields.begin(), this->Fields.end(), startsWithName);
    if (this->T.rows() != 0 || !this->T.names.empty() || !(named || isCloudCompareHeader(begin, stop)))
    {
      return false;
    }
    if (isCloudCompareHeader(begin, stop))
    {
      begin += 2; // CloudCompare writes its header line as //X,Y,Z,...
    }
    splitFields(Split::Header, begin, stop, this->Fields);
    for (const Field& f : this->Fields)
    {
      this->T.names.emplace_back(f.begin, f.end);
    }
    this->T.width = this->T.names.size();
    this->T.headerLine = this->Line;
    return true;
  }

  /// The error of a data line whose field `bad` is not a number.
  std::string notANumber(std::size_t bad) const
  {
    const std::string field(this->Fields[bad].begin, this->Fields[bad].end);
    return fail(this->Line,
      (field.empty() ? "empty field in column " + std::to_string(bad + 1)
                     : "not a number in column " + std::to_string(bad + 1) + ": '" + field + "'") +
        (this->SplitKnown ? "; this file's fields are separated by " + this->T.separators : ""));
  }

  /// A point-count line: the group before it must hold its own count.
  std::string readCount()
  {
    if (!this->countHolds())
    {
      return fail(this->CountLine, pointCountMismatch(this->Declared, this->T.rows() - this->RowsBeforeCount));
    }
    this->CountLine = this->Line;
    this->Declared = static_cast<std::size_t>(this->Row[0]);
    this->RowsBeforeCount = this->T.rows();
    ++this->T.countLines;
    return {};
  }

  /// A data row: the first fixes the separators (and, without a header, the width); every row has the width.
  std::string addRow(Split lineSplit, bool usedComma)
  {
    if (!this->SplitKnown)
    {
      this->SplitKnown = true;
      this->LineSplit = lineSplit;
      this->T.separators = describe(lineSplit);
    }
    if (this->T.width == 0)
    {
      this->T.width = this->Fields.size();
    }
    if (this->Fields.size() != this->T.width)
    {
      return fail(this->Line, "expected " + std::to_string(this->T.width) + " columns " +
          (this->T.rows() == 0 ? "as the header line names" : "like the lines before") + ", got " +
          std::to_string(this->Fields.size()));
    }
    this->T.decimalCommas = this->T.decimalCommas || usedComma;
    this->T.values.insert(this->T.values.end(), this->Row.begin(), this->Row.end());
    this->T.lines.push_back(this->Line);
    return {};
  }

  Table& T;
  bool SplitKnown = false;
  Split LineSplit = Split::Blanks;
  std::vector<Field> Fields;
  std::vector<double> Row;
  std::size_t Line = 0, CountLine = 0, Declared = 0, RowsBeforeCount = 0;
};

} // namespace

std::string readTable(const char* text, std::size_t size, Table& table, bool wholeText)
{
  table = Table();
  const char* p = text;
  const char* end = text + size;
  if (size >= 3 && std::memcmp(p, "\xEF\xBB\xBF", 3) == 0)
  {
    p += 3;
  }
  TableReader reader(table);
  std::size_t lineNumber = 0;
  std::string error;
  while (p < end && error.empty())
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
    if (begin != stop)
    {
      error = reader.read(begin, stop, lineNumber);
    }
  }
  if (error.empty())
  {
    error = reader.finish(wholeText, lineNumber);
  }
  if (!error.empty())
  {
    table = Table();
  }
  return error;
}

} // namespace pointtext
} // namespace gls
