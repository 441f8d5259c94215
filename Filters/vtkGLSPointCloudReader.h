/**
 * @class   vtkGLSPointCloudReader
 * @brief   Reads a point cloud file (XYZ, PTS, CSV, TXT, PTX, PCD): points with normals, colours, intensity, other
 *          columns.
 *
 * One point per line. Columns are named by a header line (x y z, nx ny nz, r g b or red green blue, intensity, any
 * other name), or, without a header, follow the standard layouts: 3 x y z; 4 x y z intensity; 6 x y z nx ny nz
 * (unit vectors) or x y z r g b (0-255 integers); 7 x y z intensity r g b (Leica PTS, with its point-count line);
 * 9 x y z r g b nx ny nz or x y z nx ny nz r g b. Colours are never read as normals. Fields are separated by blanks,
 * commas or semicolons (with decimal commas: "1,5;2,5;3"). The rules are in gls/PointTextParser.h and
 * docs/main-job.md.
 *
 * A Leica PTX file (.ptx: one or more scans, each with its scanner position and registration matrix) gives the
 * registered points, `Intensity`, `RGB` when the scans have colours, and `ScannerPosition` (double, 3 components:
 * the registered position of the scanner that saw each point, for Normal Estimation's per-point viewpoints); lines
 * at 0 0 0 (missing returns) are dropped (gls::parsePtx). A PCL PCD file (.pcd, ascii, binary or
 * binary_compressed) gives its x y z, normals, intensity, packed rgb as `RGB` and its other single-valued fields
 * (names without case: PDAL's X Y Z), every point in the file's order (an organized cloud's NaN points for missing
 * returns kept in their rows), and its sensor position, the VIEWPOINT's translation (PCL's default 0 0 0 included:
 * PCL's sensor origin), as the field data `ScannerPosition` (double, one tuple of 3; GLS Normal Estimation's
 * Automatic orientation turns the normals towards it; gls::parsePcd). A file of another
 * extension whose content is a PCD or PTX file (a scan renamed .txt) is read as one, and ColumnLayout says so.
 *
 * Output: a vtkPolyData with double-precision points and one vertex cell per point; point arrays `Normals`
 * (double, active normals, as given: not normalized), `RGB` (unsigned char, 3 components, 0-255, active scalars,
 * as VTK's PLY reader names them), `Intensity` (float, as given) and one double array per other named column,
 * each only when the file has it. Non-finite values are kept (the GLS filters leave such points out).
 * Normals whose length is far from 1 (|length - 1| > 0.01, zero included) give one vtkWarningMacro with their
 * count. A missing or unreadable file, a malformed line, or columns whose meaning cannot be told (the error says
 * how to name them in a header line) is a vtkErrorMacro naming the file and the line; the output is then empty
 * and RequestData returns 0.
 */
#ifndef vtkGLSPointCloudReader_h
#define vtkGLSPointCloudReader_h

#include "vtkGLSFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <string>

class VTKGLSFILTERS_EXPORT vtkGLSPointCloudReader : public vtkPolyDataAlgorithm
{
public:
  static vtkGLSPointCloudReader* New();
  vtkTypeMacro(vtkGLSPointCloudReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to read.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /// Whether the reader can read the file (ParaView's reader factory asks): true for the extensions .xyz, .pts, .ptx
  /// and .pcd; for .csv and .txt, which may hold any table, true when the file's first 64 KiB read as a point cloud
  /// (gls::pointCloudFileHeadError: columns that can be told, or a PCD or PTX file's header), so that a table that is
  /// no point cloud is left to ParaView's CSV reader.
  int CanReadFile(const char* name);

  /// The number of points a .pcd file's header announces, read from its first 64 KiB alone (the main job checks it
  /// against the memory before anything is read); -1 for the other formats (their text holds no count) and for a
  /// header that cannot be read (the error is then RequestData's).
  vtkIdType ReadAnnouncedPointCount();

  /// How the last file read was understood, e.g. "x y z r g b (6 columns, no header: 0-255 integers, so
  /// colours)"; empty before a read and after a failed one.
  vtkGetCharFromStdStringMacro(ColumnLayout);

protected:
  vtkGLSPointCloudReader();
  ~vtkGLSPointCloudReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  std::string ColumnLayout;

private:
  vtkGLSPointCloudReader(const vtkGLSPointCloudReader&) = delete;
  void operator=(const vtkGLSPointCloudReader&) = delete;
};

#endif
