/**
 * @class   vtkGLSPointCloudReader
 * @brief   Reads a text point cloud (XYZ, PTS, CSV): x y z [nx ny nz] per line.
 *
 * Fields are separated by spaces, tabs, commas or semicolons; '#' starts a comment. A file has 3 columns (x y z) or
 * 6 (x y z nx ny nz), or any number after a header line naming x, y, z and optionally nx, ny, nz (case-insensitive;
 * other columns are ignored). Output: a vtkPolyData with double-precision points, one vertex cell per point, and,
 * when the file has normals, the point array `Normals` (active normals, as given: not normalized). Non-finite
 * values are kept (the GLS filters leave such points out). A missing or unreadable file, or a malformed line, is a
 * vtkErrorMacro naming the file and the line, and RequestData returns 0.
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

  /// Whether the reader can read the file (used by ParaView): true for the extensions .xyz, .pts, .csv, .txt.
  int CanReadFile(const char* name);

protected:
  vtkGLSPointCloudReader();
  ~vtkGLSPointCloudReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;

private:
  vtkGLSPointCloudReader(const vtkGLSPointCloudReader&) = delete;
  void operator=(const vtkGLSPointCloudReader&) = delete;
};

#endif
