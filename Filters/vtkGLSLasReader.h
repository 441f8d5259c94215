/**
 * @class   vtkGLSLasReader
 * @brief   Reads a LAS file (ASPRS LAS 1.0 to 1.4, point formats 0 to 10): the lidar points and their attributes.
 *
 * Positions are X scale + offset in double precision (georeferenced coordinates keep their millimetres). The header
 * and its variable-length records are checked against the file first: a file that is not LAS, a LAS version or point
 * format outside those, a truncated file or a wrong point count, records shorter than their format, an Extra Bytes
 * record that does not fit, or points outside the header's bounds are errors that say what is wrong (the output is
 * then empty and RequestData returns 0). A LAZ file (compressed) is refused with how to decompress it; E57 is not
 * read.
 *
 * Output: a vtkPolyData with one vertex cell per point and the point arrays `Intensity` (unsigned short, as stored),
 * `ReturnNumber`, `NumberOfReturns`, `Classification` (unsigned char; formats 0-5: the class bits), `ScanAngle`
 * (float, degrees), `UserData` (unsigned char), `PointSourceId` (unsigned short), and where the format has them
 * `GpsTime` (double, seconds as stored), `RGB` (unsigned short, 3 components, as stored: 0-65535), `NIR` (unsigned
 * short), and one double array per Extra Bytes field, named as its descriptor, with its scale and offset applied.
 */
#ifndef vtkGLSLasReader_h
#define vtkGLSLasReader_h

#include "vtkGLSFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <string>

class VTKGLSFILTERS_EXPORT vtkGLSLasReader : public vtkPolyDataAlgorithm
{
public:
  static vtkGLSLasReader* New();
  vtkTypeMacro(vtkGLSLasReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to read.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /// Whether the reader can read the file (used by ParaView): true for the extensions .las and .laz (a LAZ file is
  /// then refused with how to decompress it).
  int CanReadFile(const char* name);

  /// The number of points the file's header announces, read from the header alone (the main job checks it against
  /// the memory before anything is read); -1 when the file cannot be opened or its header is refused (the error is
  /// then RequestData's).
  vtkIdType ReadAnnouncedPointCount();

  /// The last file's LAS version and point format, e.g. "LAS 1.2, point format 3, 110000 points"; empty before a read
  /// and after a failed one.
  vtkGetCharFromStdStringMacro(Description);

protected:
  vtkGLSLasReader();
  ~vtkGLSLasReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  std::string Description;

private:
  vtkGLSLasReader(const vtkGLSLasReader&) = delete;
  void operator=(const vtkGLSLasReader&) = delete;
};

#endif
