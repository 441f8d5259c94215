// What the readers and writers share (private to the module): one vertex cell per point, a file name's extension, the
// VTK array of a column's type, an array's values in another type.
#ifndef vtkGLSReaderParts_h
#define vtkGLSReaderParts_h

#include "vtkAOSDataArrayTemplate.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <limits>
#include <memory>
#include <numeric>
#include <string>
#include <type_traits>
#include <vector>

/// The VTK array of values of type T (the LAS attributes' columns).
template <typename T>
struct vtkGLSArrayOfT;
template <>
struct vtkGLSArrayOfT<std::uint8_t>
{
  using type = vtkUnsignedCharArray;
};
template <>
struct vtkGLSArrayOfT<std::uint16_t>
{
  using type = vtkUnsignedShortArray;
};
template <>
struct vtkGLSArrayOfT<float>
{
  using type = vtkFloatArray;
};
template <>
struct vtkGLSArrayOfT<double>
{
  using type = vtkDoubleArray;
};
template <typename T>
using vtkGLSArrayOf = typename vtkGLSArrayOfT<std::remove_const_t<T>>::type;

/// The values of an array as T times `factor`: the array's own memory when it holds T and the factor is 1, else a
/// converted copy kept alive in `kept` (a value out of T's range, NaN included, as 0).
template <typename T>
const T* vtkGLSValuesAs(vtkDataArray* a, double factor, std::vector<std::shared_ptr<void>>& kept)
{
  if (auto* same = vtkAOSDataArrayTemplate<T>::FastDownCast(a))
  {
    if (factor == 1.0)
    {
      return same->GetPointer(0);
    }
  }
  const int width = a->GetNumberOfComponents();
  const vtkIdType count = a->GetNumberOfTuples() * width;
  auto copy = std::make_shared<std::vector<T>>(static_cast<std::size_t>(count));
  for (vtkIdType k = 0; k < count; ++k)
  {
    const double v = a->GetComponent(k / width, static_cast<int>(k % width)) * factor;
    const bool inRange = std::is_floating_point<T>::value ||
      (v >= static_cast<double>(std::numeric_limits<T>::lowest()) &&
        v <= static_cast<double>(std::numeric_limits<T>::max()));
    (*copy)[static_cast<std::size_t>(k)] = inRange ? static_cast<T>(v) : T(0);
  }
  kept.push_back(copy);
  return copy->data();
}

/// The cells 0, 1, ..., n - 1, each one vertex.
inline vtkSmartPointer<vtkCellArray> vtkGLSVertexCells(vtkIdType n)
{
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfTuples(n + 1);
  connectivity->SetNumberOfTuples(n);
  std::iota(offsets->GetPointer(0), offsets->GetPointer(0) + n + 1, vtkIdType(0));
  std::iota(connectivity->GetPointer(0), connectivity->GetPointer(0) + n, vtkIdType(0));
  auto verts = vtkSmartPointer<vtkCellArray>::New();
  verts->SetData(offsets, connectivity);
  return verts;
}

/// The extension of a file name, lower case, without its dot ("" when there is none).
inline std::string vtkGLSFileExtension(const char* name)
{
  const std::string path = name ? name : "";
  const auto dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

#endif
