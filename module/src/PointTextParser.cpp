#include "gls/PointTextParser.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <fstream>
#include <sstream>

namespace gls
{
namespace
{

bool isSeparator(char c)
{
  return c == ' ' || c == '\t' || c == ',' || c == ';' || c == '\r';
}

/// Splits one line (without its comment) into fields.
void splitFields(const char* begin, const char* end, std::vector<std::string>& fields)
{
  fields.clear();
  const char* p = begin;
  while (p < end)
  {
    while (p < end && isSeparator(*p))
    {
      ++p;
    }
    const char* start = p;
    while (p < end && !isSeparator(*p))
    {
      ++p;
    }
    if (p > start)
    {
      fields.emplace_back(start, p);
    }
  }
}

bool parseNumber(const std::string& field, double& value)
{
  const char* first = field.data();
  const char* last = field.data() + field.size();
  if (first < last && *first == '+')
  {
    ++first;
  }
  const auto result = std::from_chars(first, last, value);
  return result.ec == std::errc() && result.ptr == last;
}

std::string lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

} // namespace

PointText parsePointText(const char* text, std::size_t size)
{
  PointText out;
  std::vector<std::string> fields;
  std::vector<double> values;
  int columns[6] = { 0, 1, 2, -1, -1, -1 }; // x y z nx ny nz
  std::size_t width = 0;                     // fields per data line, once known
  bool haveHeader = false, seenData = false;
  std::size_t lineNumber = 0;
  const char* p = text;
  const char* end = text + size;
  auto fail = [&](const std::string& what) {
    std::ostringstream msg;
    msg << "line " << lineNumber << ": " << what;
    out.error = msg.str();
    out.points.clear();
    out.normals.clear();
    return out;
  };
  while (p < end)
  {
    const char* eol = std::find(p, end, '\n');
    const char* hash = std::find(p, eol, '#');
    ++lineNumber;
    splitFields(p, hash, fields);
    p = eol < end ? eol + 1 : end;
    if (fields.empty())
    {
      continue;
    }
    values.resize(fields.size());
    bool numeric = true;
    for (std::size_t i = 0; i < fields.size() && numeric; ++i)
    {
      numeric = parseNumber(fields[i], values[i]);
    }
    if (!numeric)
    {
      if (seenData || haveHeader)
      {
        return fail("not a number in '" + fields[0] + (fields.size() > 1 ? " " + fields[1] : "") + "...'");
      }
      // A header naming the columns.
      const char* names[6] = { "x", "y", "z", "nx", "ny", "nz" };
      for (int c = 0; c < 6; ++c)
      {
        columns[c] = -1;
        for (std::size_t i = 0; i < fields.size(); ++i)
        {
          if (lower(fields[i]) == names[c])
          {
            columns[c] = static_cast<int>(i);
          }
        }
      }
      if (columns[0] < 0 || columns[1] < 0 || columns[2] < 0)
      {
        return fail("a header line must name the columns x, y and z");
      }
      const int normalColumns = (columns[3] >= 0) + (columns[4] >= 0) + (columns[5] >= 0);
      if (normalColumns != 0 && normalColumns != 3)
      {
        return fail("a header naming normals must name all of nx, ny and nz");
      }
      haveHeader = true;
      width = fields.size();
      continue;
    }
    if (!seenData && !haveHeader)
    {
      if (fields.size() != 3 && fields.size() != 6)
      {
        return fail("expected 3 (x y z) or 6 (x y z nx ny nz) columns, or a header naming them; got " +
          std::to_string(fields.size()));
      }
      width = fields.size();
      if (width == 6)
      {
        columns[3] = 3;
        columns[4] = 4;
        columns[5] = 5;
      }
    }
    if (fields.size() != width)
    {
      return fail("expected " + std::to_string(width) + " columns like the lines before, got " +
        std::to_string(fields.size()));
    }
    seenData = true;
    for (int c = 0; c < 3; ++c)
    {
      out.points.push_back(values[static_cast<std::size_t>(columns[c])]);
    }
    if (columns[3] >= 0)
    {
      for (int c = 3; c < 6; ++c)
      {
        out.normals.push_back(values[static_cast<std::size_t>(columns[c])]);
      }
    }
  }
  if (out.points.empty())
  {
    return fail("no points found");
  }
  return out;
}

PointText readPointTextFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    PointText out;
    out.error = path + ": cannot be opened (missing or not readable)";
    return out;
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  PointText out = parsePointText(text.data(), text.size());
  if (!out.error.empty())
  {
    out.error = path + ": " + out.error;
  }
  return out;
}

} // namespace gls
