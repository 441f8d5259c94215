/**
 * @class   vtkGLSLasReader
 * @brief   Reads a LAS file (ASPRS LAS 1.0 to 1.4, point formats 0 to 10): the lidar points and their attributes.
 *
 * Positions are X scale + offset in double precision: each is the file's integer exactly (georeferenced coordinates
 * keep every digit; X = (x - offset) / scale rounds back to it). The header and its variable-length records are
 * checked against the file first: a file that is not LAS, a LAS version or point format outside those, a truncated
 * file or a wrong point count, records shorter than their format, an Extra Bytes record that does not fit, or points
 * outside the header's bounds are errors that say what is wrong (the output is then empty and RequestData returns 0).
 * Common quirks of writers are read with one warning each naming the quirk: Extra Bytes fields of the deprecated
 * array types (read as 2 or 3 components), header bounds stored unscaled, a LAS 1.4 point count in the legacy field
 * only, extended records outside the file. A LAZ file (compressed) is refused with how to decompress it; E57 is not
 * read.
 *
 * Withheld points (the withheld flag: points a producer marked as not to be used) are left out unless
 * KeepWithheldPoints is on; their count is in the field data `GLSWithheldPoints` and the Description.
 *
 * Output: a vtkPolyData with one vertex cell per point and the point arrays `Intensity` (unsigned short, as stored),
 * `ReturnNumber`, `NumberOfReturns`, `Classification` (unsigned char; formats 0-5: the class bits), `ScanAngle`
 * (float, degrees), `UserData` (unsigned char), `PointSourceId` (unsigned short), the flags `Withheld`, `Synthetic`,
 * `KeyPoint`, `Overlap` (formats 0-5: class 12), `ScanDirection` and `EdgeOfFlightLine` (unsigned char, 0 or 1),
 * and where the format has them `ScannerChannel` (unsigned char 0-3, formats 6-10), `GpsTime` (double, seconds as
 * stored), `RGB` (unsigned short, 3 components, as stored: 0-65535), `NIR` (unsigned short), and one double array per
 * Extra Bytes field, named as its descriptor, with its scale and offset applied (three fields `<name>_x`, `<name>_y`,
 * `<name>_z` in a row, a vector as the GLS LAS Writer writes one, as one 3-component array `<name>`). Field data: the
 * coordinate system where the file has one, `CoordinateSystemWKT` (OGC WKT, a string) and/or `GeoKeyDirectory`
 * (unsigned short), `GeoDoubleParams` (double), `GeoAsciiParams` (string): the GeoTIFF keys as stored; `LasScale`
 * and `LasOffset` (3 doubles each). The GLS filters pass field data on, so every output downstream keeps them.
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

  /// The last file's LAS version and point format, e.g. "LAS 1.2, point format 3, 110000 points; coordinate system:
  /// WKT"; empty before a read and after a failed one.
  vtkGetCharFromStdStringMacro(Description);

  ///@{
  /// Whether the withheld points are read too (default off: they are left out, as a producer marks them not to be
  /// used; counted in the field data GLSWithheldPoints).
  vtkSetMacro(KeepWithheldPoints, vtkTypeBool);
  vtkGetMacro(KeepWithheldPoints, vtkTypeBool);
  vtkBooleanMacro(KeepWithheldPoints, vtkTypeBool);
  ///@}

protected:
  vtkGLSLasReader();
  ~vtkGLSLasReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  std::string Description;
  vtkTypeBool KeepWithheldPoints;

private:
  vtkGLSLasReader(const vtkGLSLasReader&) = delete;
  void operator=(const vtkGLSLasReader&) = delete;
};

#endif
