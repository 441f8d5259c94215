#include "gls/PointTextParser.h"

#include "TextCloudFormat.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace gls
{
namespace
{

/// Reads the text line by line, each split into numbers; says which line is wrong.
class NumberLines
{
public:
  NumberLines(const char* text, std::size_t size)
    : Text(text)
    , Size(size)
  {
  }

  /// The next non-empty line's numbers into v; false at the end of the text, or (with error set) on a field that is
  /// not a number.
  bool next(std::vector<double>& v, std::string& error)
  {
    while (this->At < this->Size)
    {
      const std::size_t begin = this->At;
      while (this->At < this->Size && this->Text[this->At] != '\n')
      {
        ++this->At;
      }
      const std::string line(this->Text + begin, this->At - begin);
      ++this->At;
      ++this->Line;
      v.clear();
      // To the line's end, not to its first NUL byte: a NUL is no number (it ended the line once, so "1\0LAS..."
      // read as "1").
      const char* p = line.c_str();
      const char* stop = p + line.size();
      while (p < stop)
      {
        while (p < stop && (*p == ' ' || *p == '\t' || *p == '\r'))
        {
          ++p;
        }
        if (p == stop)
        {
          break;
        }
        char* end = nullptr;
        errno = 0;
        const double x = std::strtod(p, &end);
        if (end == p)
        {
          error = "line " + std::to_string(this->Line) + ": not a number: '" + line + "'";
          return false;
        }
        v.push_back(x);
        p = end;
      }
      if (!v.empty())
      {
        return true;
      }
    }
    return false;
  }

  std::size_t line() const { return this->Line; }

private:
  const char* Text;
  std::size_t Size;
  std::size_t At = 0;
  std::size_t Line = 0;
};

/// One scan's header: its columns and rows, the scanner's position, the 4x4 registration matrix (rows: the axes, then
/// the translation).
struct PtxScan
{
  double columns = 0.0, rows = 0.0;
  double scanner[3] = { 0, 0, 0 };
  double m[4][4] = {};
};

/// A scan's header from its first line (already in v); "" or what is wrong.
std::string readPtxScanHeader(NumberLines& lines, std::vector<double>& v, std::string& error, PtxScan& scan)
{
  if (v.size() != 1 || !(v[0] >= 0.0) || v[0] != std::floor(v[0]))
  {
    return "line " + std::to_string(lines.line()) + ": a PTX scan begins with its column count (one integer)";
  }
  scan.columns = v[0];
  if (!lines.next(v, error) || v.size() != 1 || !(v[0] >= 0.0) || v[0] != std::floor(v[0]))
  {
    return error.empty() ? "line " + std::to_string(lines.line()) + ": the row count (one integer) expected" : error;
  }
  scan.rows = v[0];
  for (int k = 0; k < 4; ++k) // position, then the three axes
  {
    if (!lines.next(v, error) || v.size() != 3)
    {
      return error.empty() ? "line " + std::to_string(lines.line()) +
          ": 3 numbers expected (the scanner's position and axes in the PTX header)"
                           : error;
    }
    if (k == 0)
    {
      std::copy(v.begin(), v.end(), scan.scanner);
    }
  }
  for (int r = 0; r < 4; ++r)
  {
    if (!lines.next(v, error) || v.size() != 4)
    {
      return error.empty()
        ? "line " + std::to_string(lines.line()) + ": 4 numbers expected (a row of the PTX registration matrix)"
        : error;
    }
    std::copy(v.begin(), v.end(), scan.m[r]);
  }
  return {};
}

/// The scan's point lines (scan number `index`): the registered points with intensity, colours (every scan with or
/// every one without: colourColumns, -1 before the first point) and the scanner's position into out; lines at 0 0 0
/// are counted in `missing`. "" or what is wrong.
std::string readPtxScanPoints(NumberLines& lines, std::vector<double>& v, std::string& error, const PtxScan& scan,
  std::size_t index, int& colourColumns, std::size_t& missing, PointText& out)
{
  const double count = scan.columns * scan.rows;
  for (double k = 0; k < count; ++k)
  {
    if (!lines.next(v, error))
    {
      std::ostringstream msg;
      msg << (error.empty() ? "" : error + "; ") << "scan " << index << " announces " << scan.columns << " x "
          << scan.rows << " = " << count << " points, the file ends after " << k << " (truncated)";
      return msg.str();
    }
    if (v.size() != 4 && v.size() != 7)
    {
      return "line " + std::to_string(lines.line()) + ": " + std::to_string(v.size()) +
        " numbers; a PTX point line has 4 (x y z intensity) or 7 (and r g b)";
    }
    const int colours = v.size() == 7 ? 3 : 0;
    if (colourColumns >= 0 && colours != colourColumns)
    {
      return "line " + std::to_string(lines.line()) + ": points with and without colours in one file";
    }
    colourColumns = colours;
    if (v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0)
    {
      ++missing;
      continue;
    }
    for (int c = 0; c < 3; ++c)
    {
      out.points.push_back(v[0] * scan.m[0][c] + v[1] * scan.m[1][c] + v[2] * scan.m[2][c] + scan.m[3][c]);
    }
    out.intensity.push_back(static_cast<float>(v[3]));
    for (int c = 0; c < colours; ++c)
    {
      out.colors.push_back(static_cast<unsigned char>(std::min(255.0, std::max(0.0, std::round(v[4 + c])))));
    }
    out.viewpoints.insert(out.viewpoints.end(), scan.scanner, scan.scanner + 3);
  }
  return {};
}

} // namespace

namespace pointtext
{

bool beginsWithPtxHeader(const char* text, std::size_t size)
{
  NumberLines lines(text, size);
  std::vector<double> v;
  std::string error;
  PtxScan scan;
  return lines.next(v, error) && readPtxScanHeader(lines, v, error, scan).empty();
}

} // namespace pointtext

PointText parsePtx(const char* text, std::size_t size)
{
  PointText out;
  NumberLines lines(text, size);
  std::vector<double> v;
  std::string error;
  std::size_t scans = 0, missing = 0;
  int colourColumns = -1; // 0 or 3 once the first point line is read
  const auto fail = [](const std::string& what) {
    PointText failed;
    failed.error = what;
    return failed;
  };
  while (lines.next(v, error))
  {
    PtxScan scan;
    std::string problem = readPtxScanHeader(lines, v, error, scan);
    if (problem.empty())
    {
      problem = readPtxScanPoints(lines, v, error, scan, ++scans, colourColumns, missing, out);
    }
    if (!problem.empty())
    {
      return fail(problem);
    }
  }
  if (!error.empty())
  {
    return fail(error);
  }
  if (scans == 0)
  {
    return fail("no PTX scan (the file is empty)");
  }
  std::ostringstream layout;
  layout << "PTX: " << scans << " scan" << (scans > 1 ? "s" : "") << ", x y z intensity"
         << (colourColumns == 3 ? " r g b" : "") << ", " << missing << " missing returns (0 0 0) dropped";
  out.layout = layout.str();
  return out;
}

} // namespace gls
