/**
 * @class   vtkGLSPlyWriter
 * @brief   Writes a point set as a binary PLY file whose point arrays other tools load: every numeric array as
 *          properties `scalar_<name>` (CloudCompare's scalar fields, loaded without a dialog).
 *
 * Vertices: x y z in the points' own type (float32 stays float32, doubles stay doubles), `Normals` as nx ny nz
 * (float), `RGB` as red green blue (uchar; 16-bit colours divided by 257), and every other numeric point array as
 * properties `scalar_<name>` (double for a double array, such as a LAS file's GpsTime; float otherwise; a
 * 3-component array as `scalar_<name>_x`, `_y`, `_z`; blanks in names as '_').
 * Faces: the polygons of a vtkPolyData (3 to 255 points each) as vertex_indices lists; strips and lines are not
 * written. A point with a non-finite coordinate (a missing return) is left out, with the faces that use it (counted
 * in the Description, one warning). The field data's coordinate system (CoordinateSystemWKT) goes in a header
 * comment.
 *
 * Description after a write: e.g. "binary PLY, 35947 vertices (float), 12 scalar arrays, 69451 faces".
 *
 * Errors (vtkErrorMacro, nothing written): no input points, no file name, a file that cannot be written.
 */
#ifndef vtkGLSPlyWriter_h
#define vtkGLSPlyWriter_h

#include "vtkGLSFiltersModule.h"
#include "vtkGLSPointWriter.h"

class VTKGLSFILTERS_EXPORT vtkGLSPlyWriter : public vtkGLSPointWriter
{
public:
  static vtkGLSPlyWriter* New();
  vtkTypeMacro(vtkGLSPlyWriter, vtkGLSPointWriter);

protected:
  vtkGLSPlyWriter();
  ~vtkGLSPlyWriter() override;

  void WriteData() override;

private:
  vtkGLSPlyWriter(const vtkGLSPlyWriter&) = delete;
  void operator=(const vtkGLSPlyWriter&) = delete;
};

#endif
