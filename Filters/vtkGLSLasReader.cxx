#include "vtkGLSLasReader.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSReaderParts.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include "gls/FileContent.h"
#include "gls/LasFile.h"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <type_traits>

vtkStandardNewMacro(vtkGLSLasReader);

namespace
{

template <class Array>
vtkSmartPointer<Array> newArray(const char* name, int components, vtkIdType n)
{
  auto array = vtkSmartPointer<Array>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(n);
  return array;
}

} // namespace

vtkGLSLasReader::vtkGLSLasReader()
  : KeepWithheldPoints(0)
{
  this->SetNumberOfInputPorts(0);
}

vtkGLSLasReader::~vtkGLSLasReader() = default;

int vtkGLSLasReader::CanReadFile(const char* name)
{
  const std::string ext = vtkGLSFileExtension(name);
  return ext == "las" || ext == "laz";
}

vtkIdType vtkGLSLasReader::ReadAnnouncedPointCount()
{
  std::ifstream in(this->FileName, std::ios::binary);
  if (this->FileName.empty() || !in)
  {
    return -1;
  }
  in.seekg(0, std::ios::end);
  gls::LasHeader h;
  std::string error;
  return gls::readLasHeader(in, static_cast<std::uint64_t>(in.tellg()), h, error)
    ? static_cast<vtkIdType>(h.pointCount)
    : -1;
}

namespace
{

/// The point arrays of a LAS file's points: those of every format, and GpsTime, RGB, NIR, ScannerChannel and the
/// extra bytes where the file has them.
struct LasArrays
{
  vtkSmartPointer<vtkDoubleArray> xyz;
  std::vector<vtkSmartPointer<vtkDataArray>> attributes; ///< the point arrays, in output order
  gls::LasColumns columns;                               ///< where readLasPoints writes each

  LasArrays(const gls::LasHeader& h, vtkIdType n)
  {
    xyz = newArray<vtkDoubleArray>("Points", 3, n);
    columns.xyz = xyz->GetPointer(0);
    // Every attribute the format holds, named and typed as the table of gls/LasFile.h says.
    gls::forEachLasAttribute(columns, [&](const char* name, int components, gls::LasPresence presence, auto& column) {
      using Value = std::remove_pointer_t<std::remove_reference_t<decltype(column)>>;
      if (gls::presentIn(presence, h.format))
      {
        column = add<vtkGLSArrayOf<Value>>(name, components, n);
      }
    });
    for (const gls::LasExtraBytes& x : h.extra)
    {
      columns.extra.push_back(add<vtkDoubleArray>(x.name.c_str(), x.components, n));
    }
  }

  /// The points (the first `written`), one vertex cell each, and the point arrays into `output`.
  void moveInto(vtkPolyData* output, vtkIdType written) const
  {
    xyz->SetNumberOfTuples(written); // fewer than allocated when withheld points were left out
    vtkNew<vtkPoints> points;
    points->SetData(xyz);
    output->SetPoints(points);
    output->SetVerts(vtkGLSVertexCells(written));
    for (std::size_t k = 0; k < attributes.size(); ++k)
    {
      attributes[k]->SetNumberOfTuples(written);
      const vtkSmartPointer<vtkDataArray> vector =
        k + 2 < attributes.size() ? VectorOf(attributes[k], attributes[k + 1], attributes[k + 2]) : nullptr;
      output->GetPointData()->AddArray(vector ? vector.Get() : attributes[k].Get());
      k += vector ? 2 : 0;
    }
  }

  /// Three Extra Bytes fields `<name>_x`, `<name>_y`, `<name>_z` (a vector the GLS LAS Writer wrote, such as
  /// Normals) as one 3-component array `<name>`; null for any other three arrays.
  static vtkSmartPointer<vtkDataArray> VectorOf(vtkDataArray* x, vtkDataArray* y, vtkDataArray* z)
  {
    const std::string nx = x->GetName() ? x->GetName() : "", ny = y->GetName() ? y->GetName() : "",
                      nz = z->GetName() ? z->GetName() : "";
    const std::size_t base = nx.size() >= 2 ? nx.size() - 2 : 0;
    const bool named = base > 0 && nx.compare(base, 2, "_x") == 0 && ny == nx.substr(0, base) + "_y" &&
      nz == nx.substr(0, base) + "_z";
    auto* dx = vtkDoubleArray::SafeDownCast(x);
    auto* dy = vtkDoubleArray::SafeDownCast(y);
    auto* dz = vtkDoubleArray::SafeDownCast(z);
    if (!named || !dx || !dy || !dz || dx->GetNumberOfComponents() != 1 || dy->GetNumberOfComponents() != 1 ||
      dz->GetNumberOfComponents() != 1)
    {
      return nullptr;
    }
    const vtkIdType n = dx->GetNumberOfTuples();
    auto v = newArray<vtkDoubleArray>(nx.substr(0, base).c_str(), 3, n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      v->SetTypedComponent(i, 0, dx->GetValue(i));
      v->SetTypedComponent(i, 1, dy->GetValue(i));
      v->SetTypedComponent(i, 2, dz->GetValue(i));
    }
    return v;
  }

private:
  /// A new point array of n tuples, listed among the attributes; where its values go.
  template <class Array>
  typename Array::ValueType* add(const char* name, int components, vtkIdType n)
  {
    auto array = newArray<Array>(name, components, n);
    attributes.push_back(array);
    return array->GetPointer(0);
  }
};

/// The coordinate system into the field data: CoordinateSystemWKT (a string), and GeoKeyDirectory (unsigned short),
/// GeoDoubleParams (double) and GeoAsciiParams (a string) where the file has them.
void AddCoordinateSystem(const gls::LasCoordinateSystem& cs, vtkFieldData* fd)
{
  if (!cs.wkt.empty())
  {
    vtkNew<vtkStringArray> wkt;
    wkt->SetName(vtkGLSArrayNames::CoordinateSystemWKT);
    wkt->InsertNextValue(cs.wkt);
    fd->AddArray(wkt);
  }
  if (!cs.geoKeys.empty())
  {
    vtkNew<vtkUnsignedShortArray> keys;
    keys->SetName(vtkGLSArrayNames::GeoKeyDirectory);
    for (std::uint16_t k : cs.geoKeys)
    {
      keys->InsertNextValue(k);
    }
    fd->AddArray(keys);
  }
  if (!cs.geoDoubles.empty())
  {
    vtkNew<vtkDoubleArray> doubles;
    doubles->SetName(vtkGLSArrayNames::GeoDoubleParams);
    for (double d : cs.geoDoubles)
    {
      doubles->InsertNextValue(d);
    }
    fd->AddArray(doubles);
  }
  if (!cs.geoAscii.empty())
  {
    vtkNew<vtkStringArray> ascii;
    ascii->SetName(vtkGLSArrayNames::GeoAsciiParams);
    ascii->InsertNextValue(cs.geoAscii);
    fd->AddArray(ascii);
  }
}

/// A field-data array of one tuple of 3 doubles.
void AddTriple(vtkFieldData* fd, const char* name, const double* v)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(3);
  a->InsertNextTuple(v);
  fd->AddArray(a);
}

} // namespace

int vtkGLSLasReader::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->Description.clear();
  std::ifstream in(this->FileName, std::ios::binary);
  if (this->FileName.empty() || !in)
  {
    vtkErrorMacro("Cannot open the LAS file '" << this->FileName << "'.");
    return 0;
  }
  in.seekg(0, std::ios::end);
  const std::uint64_t size = static_cast<std::uint64_t>(in.tellg());
  gls::LasHeader h;
  std::string error;
  if (!gls::readLasHeader(in, size, h, error))
  {
    vtkErrorMacro("Cannot read the LAS file '" << this->FileName << "': " << gls::printableText(error) << ".");
    return 0;
  }
  const vtkIdType n = static_cast<vtkIdType>(h.pointCount);
  LasArrays arrays(h, n);
  arrays.columns.skipWithheld = !this->KeepWithheldPoints;
  gls::LasReadResult read;
  if (!gls::readLasPoints(in, h, arrays.columns, read, error))
  {
    vtkErrorMacro("Cannot read the LAS file '" << this->FileName << "': " << gls::printableText(error) << ".");
    return 0;
  }
  std::vector<std::string> quirks = h.quirks;
  quirks.insert(quirks.end(), read.quirks.begin(), read.quirks.end());
  for (const std::string& quirk : quirks)
  {
    vtkWarningMacro("The LAS file '" << this->FileName << "' is read although " << gls::printableText(quirk) << ".");
  }
  arrays.moveInto(output, static_cast<vtkIdType>(read.written));
  vtkFieldData* fd = output->GetFieldData();
  AddCoordinateSystem(h.coordinateSystem, fd);
  AddTriple(fd, vtkGLSArrayNames::LasScale, h.scale);
  AddTriple(fd, vtkGLSArrayNames::LasOffset, h.offset);
  const std::uint64_t left = this->KeepWithheldPoints ? 0 : read.withheld;
  if (left > 0)
  {
    vtkNew<vtkIdTypeArray> withheld;
    withheld->SetName(vtkGLSArrayNames::WithheldPoints);
    withheld->InsertNextValue(static_cast<vtkIdType>(left));
    fd->AddArray(withheld);
  }
  std::ostringstream d;
  d << "LAS " << h.versionMajor << "." << h.versionMinor << ", point format " << h.format << ", " << h.pointCount
    << " points";
  if (left > 0)
  {
    d << " (" << left << " withheld, left out)";
  }
  else if (read.withheld > 0)
  {
    d << " (" << read.withheld << " withheld, kept)";
  }
  const gls::LasCoordinateSystem& cs = h.coordinateSystem;
  d << (cs.empty() ? "; no coordinate system"
                   : std::string("; coordinate system: ") + (cs.wkt.empty() ? "" : "WKT") +
          (cs.wkt.empty() || cs.geoKeys.empty() ? "" : " and ") + (cs.geoKeys.empty() ? "" : "GeoTIFF keys"));
  this->Description = d.str();
  return 1;
}

void vtkGLSLasReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "KeepWithheldPoints: " << this->KeepWithheldPoints << "\n";
  os << indent << "Description: " << this->Description << "\n";
}
