#include "vtkGLSLasWriter.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSReaderParts.h"

#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkStringArray.h"

#include "gls/LasWriter.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <set>
#include <sstream>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkGLSLasWriter);

vtkGLSLasWriter::vtkGLSLasWriter() = default;

vtkGLSLasWriter::~vtkGLSLasWriter() = default;

namespace
{

/// The field data's array `name` of one tuple of 3 values, into v; false when absent or not finite.
bool Triple(vtkFieldData* fd, const char* name, double v[3])
{
  vtkDataArray* a = fd->GetArray(name);
  if (!a || a->GetNumberOfTuples() != 1 || a->GetNumberOfComponents() != 3)
  {
    return false;
  }
  a->GetTuple(0, v);
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

/// The coordinate system the field data carries (a LAS file's, as the GLS LAS Reader gives it).
gls::LasCoordinateSystem CoordinateSystemOf(vtkFieldData* fd)
{
  gls::LasCoordinateSystem cs;
  if (auto* wkt = vtkStringArray::SafeDownCast(fd->GetAbstractArray(vtkGLSArrayNames::CoordinateSystemWKT)))
  {
    cs.wkt = wkt->GetNumberOfValues() > 0 ? wkt->GetValue(0) : "";
  }
  if (vtkDataArray* keys = fd->GetArray(vtkGLSArrayNames::GeoKeyDirectory))
  {
    for (vtkIdType k = 0; k < keys->GetNumberOfTuples(); ++k)
    {
      cs.geoKeys.push_back(static_cast<std::uint16_t>(keys->GetComponent(k, 0)));
    }
  }
  if (vtkDataArray* doubles = fd->GetArray(vtkGLSArrayNames::GeoDoubleParams))
  {
    for (vtkIdType k = 0; k < doubles->GetNumberOfTuples(); ++k)
    {
      cs.geoDoubles.push_back(doubles->GetComponent(k, 0));
    }
  }
  if (auto* ascii = vtkStringArray::SafeDownCast(fd->GetAbstractArray(vtkGLSArrayNames::GeoAsciiParams)))
  {
    cs.geoAscii = ascii->GetNumberOfValues() > 0 ? ascii->GetValue(0) : "";
  }
  return cs;
}

} // namespace

void vtkGLSLasWriter::WriteData()
{
  std::vector<double> xyz;
  vtkPointSet* input = this->InputPositions(xyz);
  if (!input)
  {
    return;
  }
  const vtkIdType n = input->GetNumberOfPoints();
  gls::LasWriteSource source;
  source.n = static_cast<std::size_t>(n);
  source.xyz = xyz.data();
  vtkFieldData* fd = input->GetFieldData();
  // The input's own scale and offset where it came from a LAS file (its integers back) and they still hold its
  // positions, else chosen.
  const bool own = Triple(fd, vtkGLSArrayNames::LasScale, source.scale) &&
    Triple(fd, vtkGLSArrayNames::LasOffset, source.offset) && source.scale[0] > 0.0 && source.scale[1] > 0.0 &&
    source.scale[2] > 0.0 && gls::lasIntegersHold(xyz.data(), source.n, source.scale, source.offset);
  if (!own && !gls::chooseLasScaleAndOffset(xyz.data(), source.n, source.scale, source.offset))
  {
    vtkErrorMacro("No point of the input has finite coordinates: nothing to write to '" << this->FileName << "'.");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  source.coordinateSystem = CoordinateSystemOf(fd);
  // The attributes by their names (the table of gls/LasFile.h), the other numeric arrays as Extra Bytes.
  vtkPointData* pd = input->GetPointData();
  std::vector<std::shared_ptr<void>> kept;
  std::set<std::string> taken;
  gls::forEachLasAttribute(source, [&](const char* name, int components, gls::LasPresence, auto& column) {
    using Value = std::remove_const_t<std::remove_pointer_t<std::remove_reference_t<decltype(column)>>>;
    vtkDataArray* a = pd->GetArray(name);
    if (a && a->GetNumberOfComponents() == components && a->GetNumberOfTuples() == n)
    {
      // 0-255 colours (a PLY's, a text file's) as LAS's 16 bits.
      const bool byteColours = std::string(name) == vtkGLSArrayNames::Colors && a->GetDataType() == VTK_UNSIGNED_CHAR;
      column = vtkGLSValuesAs<Value>(a, byteColours ? 257.0 : 1.0, kept);
      taken.insert(name);
    }
  });
  for (int k = 0; k < pd->GetNumberOfArrays(); ++k)
  {
    vtkDataArray* a = pd->GetArray(k);
    if (!a || !a->GetName() || taken.count(a->GetName()) || a->GetNumberOfTuples() != n)
    {
      continue;
    }
    gls::LasExtraSource e;
    e.name = a->GetName();
    e.description = std::string("GLS: ") + a->GetName();
    e.components = a->GetNumberOfComponents();
    PerPointValues(a, e.floats, e.doubles, kept);
    source.extra.push_back(e);
  }
  gls::LasWriteResult result;
  if (!this->WriteStream("LAS", [&](std::ostream& out, std::string& error) {
        return gls::writeLas(out, source, result, error);
      }))
  {
    return;
  }
  this->WarnPointsLeftOut(result.leftOut, source.n, "LAS has no NaN");
  std::size_t fields = 0;
  for (const gls::LasExtraSource& e : source.extra)
  {
    fields += static_cast<std::size_t>(e.components);
  }
  std::ostringstream d;
  d << "LAS 1.4, point format " << result.format << ", " << result.written << " points";
  if (result.leftOut > 0)
  {
    d << " (" << result.leftOut << " with a non-finite coordinate left out)";
  }
  d << ", " << fields << " Extra Bytes fields; scale " << source.scale[0] << " " << source.scale[1] << " "
    << source.scale[2] << (own ? ", the input's own" : ", chosen for the points' extent");
  this->Description = d.str();
}
