// Parser of text point clouds (XYZ, PTS, CSV, TXT): one point per line. Never throws; malformed input gives an
// error naming its line. Numbers are read locale-independently. docs/main-job.md shows the layouts with examples.
//
// Lines: '#' starts a comment; blank lines are skipped; a UTF-8 byte-order mark is skipped; fields may be quoted
// ("1.5"). A line holding one non-negative integer is a point-count line (Leica PTS, CloudCompare): the points that
// follow it, up to the next count line or the end, must be that many.
//
// Separators are chosen by the first data line (a line of numbers with more than one field):
//   - it contains ';': fields are separated by ';' (and blanks); a comma between two digits is a decimal comma
//     (European CSV: "1,5;2,25;3");
//   - else it contains ',' that is not between two digits of blank-separated fields: fields are separated by ','
//     (and blanks), the decimal mark is '.';
//   - else fields are separated by blanks (spaces, tabs); a comma between two digits is a decimal comma
//     ("1,5 2,25 3").
// Every line must then use the same separators; a line that does not reads as "not a number" with its number.
//
// Columns, by a header line (a line before the data with a field that starts with a letter or '_', or that starts
// with "//" as CloudCompare writes it, which is ignored; separators: blanks, ',' or ';'), names compared without
// case:
//   x y z (required); nx ny nz, normal_x normal_y normal_z or normalx normaly normalz (normals, all three or none);
//   r g b, red green blue or rf gf bf (colours, all three or none); intensity; any other name is kept as a column
//   of its own (PointText::otherColumns) under that name.
// Without a header, by the number of columns (the standard layouts):
//   3: x y z;   4: x y z intensity;
//   6: x y z nx ny nz when columns 4-6 are unit vectors (|length - 1| <= unitLengthTolerance, zero or non-finite
//      vectors allowed), else x y z r g b when they are integers in [0, 255], else an error asking for a header;
//   7: x y z intensity r g b (Leica PTS; columns 5-7 must be colour values, else an error asking for a header);
//   9: x y z r g b nx ny nz (CloudCompare's order) or x y z nx ny nz r g b, whichever triple is unit vectors
//      beside a triple of colour values; an error asking for a header when neither or both fit;
//   any other count: an error listing these layouts.
// Colour values: when every value of the three columns is in [0, 1] they are fractions (scaled by 255 and rounded),
// else each must be an integer in [0, 255]; anything else is an error with its line. Normals are kept as given (the
// GLS filters normalize them and leave zero or non-finite ones out); normals whose length is far from 1
// (|length - 1| > unitLengthTolerance, zero and non-finite included) give PointText::warning with their count.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace gls
{

/// Largest |length - 1| of a vector read as a unit normal: 0.01 admits normals written with two decimals
/// (each component off by at most 0.005 moves the length by at most 0.0087).
constexpr double unitLengthTolerance = 0.01;

/// A column the parser keeps under the name its header gives it (not x, y, z, normals, colours or intensity).
struct PointTextColumn
{
  std::string name;           ///< as in the header
  std::vector<double> values; ///< one per point
};

struct PointText
{
  std::vector<double> points;                ///< 3 per point
  std::vector<double> normals;               ///< 3 per point, as given, or empty when the file has none
  std::vector<unsigned char> colors;         ///< r g b per point (0-255), or empty
  std::vector<float> intensity;              ///< 1 per point, as given, or empty
  std::vector<PointTextColumn> otherColumns; ///< the header's other named columns, in file order
  std::vector<double> viewpoints;            ///< 3 per point: the position of the scanner that saw it (PTX), or empty
  bool hasSensor = false;                    ///< the file gives one sensor position for every point (PCD)
  double sensor[3] = { 0.0, 0.0, 0.0 };      ///< that position, when hasSensor
  std::string layout;  ///< how the columns were read, e.g. "x y z r g b (6 columns, no header: 0-255 integers)"
  std::string warning; ///< empty, or what the caller should report (normals far from unit length, with the count)
  std::string error;   ///< empty on success, else "line N: what is wrong" (the other members are then empty)
};

/// Parses `size` bytes of text.
PointText parsePointText(const char* text, std::size_t size);

/// Reads and parses a file; error names the file when it cannot be read. A file whose content is a PCL PCD or a
/// Leica PTX file (textCloudFormat), whatever its extension (.txt, .csv), is read as one, and its layout says so.
PointText readPointTextFile(const std::string& path);

/// The format a text file's first bytes show, whatever its extension.
enum class TextCloudFormat
{
  PointText, ///< anything else: the point text above
  Pcd,       ///< a PCL PCD header: the first line that is not blank or a '#' comment starts with VERSION or FIELDS
  Ptx        ///< a Leica PTX scan header as parsePtx reads it: two lines of one integer count, four lines of three
             ///< numbers, four of four
};
TextCloudFormat textCloudFormat(const char* head, std::size_t size);

/// "" when the first `size` bytes of a file read as a point cloud: a PCD or PTX header (textCloudFormat), or point
/// text whose columns can be told by the rules above, judged on its complete lines (with `wholeFile` false the last
/// line, when not ended by a newline, is left out, and the last point-count group may hold fewer points than it
/// says). Else why not: parsePointText's error. ParaView's reader factory asks this of .csv and .txt files, to choose
/// between the point-cloud reader and its table reader.
std::string pointCloudHeadError(const char* head, std::size_t size, bool wholeFile);

/// Bytes of a file that pointCloudFileHeadError reads.
constexpr std::size_t pointCloudHeadBytes = 64 * 1024;

/// pointCloudHeadError of a file's first pointCloudHeadBytes; an error naming the file when it cannot be opened.
std::string pointCloudFileHeadError(const std::string& path);

/// A Leica PTX file (one or more scans, each: its columns and rows, the scanner's registered position and axes, a 4x4
/// registration matrix whose first three rows are the axes and the last the translation, then columns x rows lines
/// `x y z intensity [r g b]` in the scanner's frame): the registered points (x row 0 + y row 1 + z row 2 + row 3),
/// intensity, colours when the scan has them, and each point's scanner position (viewpoints). Lines at 0 0 0 are
/// missing returns and are dropped (their count is in the layout). A scan with fewer lines than announced, a
/// malformed header or line, or scans with and without colours mixed is an error with the line.
PointText parsePtx(const char* text, std::size_t size);

/// parsePtx of a file (errors prefixed with its path).
PointText readPtxFile(const std::string& path);

/// A PCL PCD file (version .7; DATA ascii, binary or binary_compressed, LZF): fields x y z (required), normal_x
/// normal_y normal_z as normals, intensity, rgb or rgba (packed 0x00RRGGBB, as PCL writes them) as colours, the other
/// single-valued fields as other columns (fields of several values are skipped, said in the layout); field names
/// are compared without case (PDAL writes X Y Z Intensity). The VIEWPOINT's translation is the sensor's position
/// (sensor; PCL's convention: its default 0 0 0 1 0 0 0, or no VIEWPOINT line, is a sensor at the origin, towards
/// which PCL turns normals). NaN points are kept, in the file's order (an organized cloud's rows and columns,
/// WIDTH x HEIGHT, said in the layout). A malformed header, a count the
/// file cannot hold, truncated or damaged (LZF) data is an error saying what is wrong.
PointText parsePcd(const char* data, std::size_t size);

/// parsePcd of a file (errors prefixed with its path).
PointText readPcdFile(const std::string& path);

/// The number of points a PCD header announces (POINTS, or WIDTH x HEIGHT without it), from a file's first bytes
/// (the header and the DATA line among them); -1 when they hold no readable PCD header.
long long pcdAnnouncedPoints(const char* head, std::size_t size);

} // namespace gls
