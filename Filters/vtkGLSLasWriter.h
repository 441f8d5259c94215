/**
 * @class   vtkGLSLasWriter
 * @brief   Writes a point set as a LAS 1.4 file: its points, their lidar attributes, and every other point array as
 *          float32 Extra Bytes fields (the GLS results as dimensions of a LAS file, for PDAL, LAStools, QGIS).
 *
 * The points are written in point format 6, 7 (when the input has a 3-component `RGB` array) or 8 (and `NIR`), with
 * the attributes the GLS LAS Reader reads, found by their names (`Intensity`, `ReturnNumber`, `NumberOfReturns`,
 * `Classification`, `ScanAngle`, `UserData`, `PointSourceId`, the flags, `ScannerChannel`, `GpsTime`, `RGB`, `NIR`;
 * a missing one is written as 0, one return of one; another type is converted, 0-255 colours scaled to 16 bits).
 * Every other numeric point array becomes Extra Bytes fields of float32 values, one per component (a vector's named
 * `<name>_x`, `_y`, `_z`), its name cut to LAS's 32 characters: the GLS arrays (`GLSFeature`, the summaries,
 * `Normals`, ...) are read back by the GLS LAS Reader under the same names.
 *
 * Positions: a point set read from a LAS file (field data `LasScale` and `LasOffset`) is written with its own scale
 * and offset while they hold its positions, so every position is the file's integer again; any other with
 * gls::chooseLasScaleAndOffset's (per axis the lowest coordinate and the finest power of ten whose 32-bit integers
 * hold the extent: a position moves by at most half of it, 5e-11 on a 0.2 m object, 5e-7 on a 1 km tile). A point
 * with a non-finite coordinate (a missing return) is not written: LAS has no NaN (counted in the Description, one
 * warning). The coordinate system of the field data (`CoordinateSystemWKT`, the GeoTIFF keys) is written as LAS
 * records.
 *
 * Description after a write: e.g. "LAS 1.4, point format 6, 35947 points, 12 Extra Bytes fields; scale 1e-10 1e-10
 * 1e-10, chosen for the points' extent".
 *
 * Errors (vtkErrorMacro, nothing written): no input points, no file name, a file that cannot be written.
 */
#ifndef vtkGLSLasWriter_h
#define vtkGLSLasWriter_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSPointWriter.h"

class VTKGLSFILTERS_EXPORT vtkGLSLasWriter : public vtkGLSPointWriter
{
public:
  static vtkGLSLasWriter* New();
  vtkTypeMacro(vtkGLSLasWriter, vtkGLSPointWriter);

protected:
  vtkGLSLasWriter();
  ~vtkGLSLasWriter() override;

  void WriteData() override;

private:
  vtkGLSLasWriter(const vtkGLSLasWriter&) = delete;
  void operator=(const vtkGLSLasWriter&) = delete;
};

#endif
