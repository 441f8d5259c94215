#include "PointTextLayout.h"

#include "gls/PointTextParser.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

namespace gls
{
namespace pointtext
{
namespace
{

enum Role
{
  X,
  Y,
  Z,
  NX,
  NY,
  NZ,
  R,
  G,
  B,
  Intensity,
  RoleCount
};

const char* const roleNames[RoleCount] = { "x", "y", "z", "nx", "ny", "nz", "r", "g", "b", "intensity" };

/// The role a header name gives its column, or -1 for a column kept under its own name.
int roleOf(std::string name)
{
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  static const struct
  {
    const char* name;
    int role;
  } known[] = { { "x", X }, { "y", Y }, { "z", Z }, { "nx", NX }, { "ny", NY }, { "nz", NZ }, { "normal_x", NX },
    { "normal_y", NY }, { "normal_z", NZ }, { "normalx", NX }, { "normaly", NY }, { "normalz", NZ }, { "r", R },
    { "g", G }, { "b", B }, { "red", R }, { "green", G }, { "blue", B }, { "rf", R }, { "gf", G }, { "bf", B },
    { "intensity", Intensity } };
  for (const auto& k : known)
  {
    if (name == k.name)
    {
      return k.role;
    }
  }
  return -1;
}

std::string line(std::size_t number)
{
  return "line " + std::to_string(number);
}

std::string number(double value)
{
  std::ostringstream s;
  s << value;
  return s.str();
}

/// Whether the three columns are unit vectors (zero or non-finite ones allowed, at least one unit); if not, the
/// first row that is not and its length.
struct UnitCheck
{
  bool unit = false;
  std::size_t row = 0;
  double length = 0;
};

UnitCheck checkUnit(const Table& t, const int c[3])
{
  UnitCheck out;
  for (std::size_t row = 0; row < t.rows(); ++row)
  {
    const double length = std::hypot(t.at(row, c[0]), t.at(row, c[1]), t.at(row, c[2]));
    if (!std::isfinite(length) || length == 0)
    {
      continue;
    }
    if (std::abs(length - 1) > unitLengthTolerance)
    {
      out.unit = false;
      out.row = row;
      out.length = length;
      return out;
    }
    out.unit = true;
  }
  if (!out.unit && t.rows() > 0) // no vector of non-zero finite length
  {
    out.length = std::hypot(t.at(0, c[0]), t.at(0, c[1]), t.at(0, c[2]));
  }
  return out;
}

/// Whether every value of the three columns is in [0, 1] (fractions), and the first row holding a value that is
/// not an integer in [0, 255] (npos when none does).
struct ColorCheck
{
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);
  bool fractions = true;
  std::size_t badRow = npos;
  double badValue = 0;
  bool colors() const { return fractions || badRow == npos; }
};

ColorCheck checkColors(const Table& t, const int c[3])
{
  ColorCheck out;
  for (std::size_t row = 0; row < t.rows(); ++row)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double v = t.at(row, c[k]);
      out.fractions = out.fractions && v >= 0 && v <= 1;
      if (out.badRow == ColorCheck::npos && !(v >= 0 && v <= 255 && std::floor(v) == v))
      {
        out.badRow = row;
        out.badValue = v;
      }
    }
  }
  return out;
}

void setTriple(int target[3], int first)
{
  for (int k = 0; k < 3; ++k)
  {
    target[k] = first + k;
  }
}

std::string byHeader(const Table& t, Layout& layout)
{
  int column[RoleCount];
  std::fill(column, column + RoleCount, -1);
  std::string roles;
  for (std::size_t i = 0; i < t.names.size(); ++i)
  {
    const int role = roleOf(t.names[i]);
    roles += (i ? " " : "") + (role < 0 ? t.names[i] : std::string(roleNames[role]));
    if (role < 0)
    {
      layout.others.push_back(static_cast<int>(i));
    }
    else if (column[role] >= 0)
    {
      return line(t.headerLine) + ": columns " + std::to_string(column[role] + 1) + " and " +
        std::to_string(i + 1) + " both name " + roleNames[role];
    }
    else
    {
      column[role] = static_cast<int>(i);
    }
  }
  if (column[X] < 0 || column[Y] < 0 || column[Z] < 0)
  {
    return line(t.headerLine) + ": a header line must name the columns x, y and z";
  }
  const auto named = [&](int first) {
    return (column[first] >= 0) + (column[first + 1] >= 0) + (column[first + 2] >= 0);
  };
  if (named(NX) != 0 && named(NX) != 3)
  {
    return line(t.headerLine) + ": a header naming normals must name all of nx, ny and nz";
  }
  if (named(R) != 0 && named(R) != 3)
  {
    return line(t.headerLine) + ": a header naming colours must name all of r, g and b (or red, green, blue)";
  }
  std::copy(column + X, column + X + 3, layout.xyz);
  if (named(NX) == 3)
  {
    std::copy(column + NX, column + NX + 3, layout.normals);
  }
  if (named(R) == 3)
  {
    std::copy(column + R, column + R + 3, layout.colors);
    const ColorCheck colors = checkColors(t, layout.colors);
    if (!colors.colors())
    {
      return line(t.lines[colors.badRow]) + ": colour value " + number(colors.badValue) +
        ": the colour columns must hold integers in [0, 255], or only fractions in [0, 1]";
    }
    layout.colorFractions = colors.fractions;
  }
  layout.intensity = column[Intensity];
  layout.description = roles + " (header " + line(t.headerLine) + ")";
  return {};
}

std::string askForHeader()
{
  return "; add a header line naming the columns, e.g. 'x y z nx ny nz' or 'x y z r g b'";
}

std::string byColumnCount(const Table& t, Layout& layout)
{
  const std::string first = line(t.lines[0]);
  const std::string columns = " (" + std::to_string(t.width) + " columns, no header";
  setTriple(layout.xyz, 0);
  switch (t.width)
  {
    case 3:
      layout.description = "x y z" + columns + ")";
      return {};
    case 4:
      layout.intensity = 3;
      layout.description = "x y z intensity" + columns + ")";
      return {};
    case 6:
    {
      int triple[3] = { 3, 4, 5 };
      const UnitCheck unit = checkUnit(t, triple);
      const ColorCheck colors = checkColors(t, triple);
      if (unit.unit)
      {
        setTriple(layout.normals, 3);
        layout.description = "x y z nx ny nz" + columns + ": unit vectors, so normals)";
        return {};
      }
      if (colors.badRow == ColorCheck::npos)
      {
        setTriple(layout.colors, 3);
        layout.colorFractions = colors.fractions;
        layout.description = "x y z r g b" + columns + ": 0-255 integers, so colours)";
        return {};
      }
      return first + ": 6 columns without a header, but columns 4-6 are neither unit normals (" +
        line(t.lines[unit.row]) + ": length " + number(unit.length) + ") nor 0-255 integer colours (" +
        line(t.lines[colors.badRow]) + ": " + number(colors.badValue) + ")" + askForHeader();
    }
    case 7:
    {
      int triple[3] = { 4, 5, 6 };
      const ColorCheck colors = checkColors(t, triple);
      if (!colors.colors())
      {
        return first + ": 7 columns without a header are read as x y z intensity r g b (Leica PTS), but columns "
                        "5-7 are not colours (" +
          line(t.lines[colors.badRow]) + ": " + number(colors.badValue) + ")" + askForHeader();
      }
      layout.intensity = 3;
      setTriple(layout.colors, 4);
      layout.colorFractions = colors.fractions;
      layout.description = "x y z intensity r g b" + columns + ": Leica PTS)";
      return {};
    }
    case 9:
    {
      int a[3] = { 3, 4, 5 }, b[3] = { 6, 7, 8 };
      const bool aUnit = checkUnit(t, a).unit, bUnit = checkUnit(t, b).unit;
      const ColorCheck aColors = checkColors(t, a), bColors = checkColors(t, b);
      const bool colorsFirst = aColors.colors() && bUnit, normalsFirst = aUnit && bColors.colors();
      if (colorsFirst != normalsFirst)
      {
        setTriple(layout.colors, colorsFirst ? 3 : 6);
        setTriple(layout.normals, colorsFirst ? 6 : 3);
        layout.colorFractions = (colorsFirst ? aColors : bColors).fractions;
        layout.description = (colorsFirst ? "x y z r g b nx ny nz" : "x y z nx ny nz r g b") + columns +
          (colorsFirst ? ": CloudCompare's order)" : ")");
        return {};
      }
      return first + ": 9 columns without a header are read as x y z r g b nx ny nz or x y z nx ny nz r g b, but " +
        (colorsFirst ? std::string("both columns 4-6 and 7-9 could be the normals")
                     : std::string("neither columns 4-6 nor 7-9 are unit normals beside colour values")) +
        askForHeader();
    }
    default:
      return first + ": " + std::to_string(t.width) +
        " columns without a header: expected 3 (x y z), 4 (x y z intensity), 6 (x y z nx ny nz, or x y z r g b), "
        "7 (x y z intensity r g b) or 9 (x y z r g b nx ny nz, or x y z nx ny nz r g b), or a header line naming "
        "the columns";
  }
}

} // namespace

std::string chooseLayout(const Table& table, Layout& layout)
{
  layout = Layout();
  const std::string error = table.names.empty() ? byColumnCount(table, layout) : byHeader(table, layout);
  if (error.empty() && layout.colors[0] >= 0 && layout.colorFractions)
  {
    layout.description += "; colours as 0-1 fractions";
  }
  return error;
}

} // namespace pointtext
} // namespace gls
