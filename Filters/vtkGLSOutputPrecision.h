// The arrays a filter writes under its OutputPrecision property (private to the module; GLS Normal Estimation and GLS
// Continuous Features): vtkAlgorithm::DOUBLE_PRECISION gives doubles, SINGLE_PRECISION floats, each value the float
// nearest the double computed.
#ifndef vtkGLSOutputPrecision_h
#define vtkGLSOutputPrecision_h

#include "vtkAlgorithm.h"
#include "vtkDataArray.h"
#include "vtkSmartPointer.h"

namespace vtkGLSOutputPrecision
{

/// True when the precision asks for floats.
inline bool IsSingle(int precision)
{
  return precision == vtkAlgorithm::SINGLE_PRECISION;
}

/// The bytes of one value written at this precision.
inline double ValueBytes(int precision)
{
  return IsSingle(precision) ? sizeof(float) : sizeof(double);
}

/// Its name ("Single" or "Double"), for PrintSelf.
inline const char* Name(int precision)
{
  return IsSingle(precision) ? "Single" : "Double";
}

/// A named array of `tuples` tuples of `components` values at this precision (values not yet written).
inline vtkSmartPointer<vtkDataArray> NewArray(const char* name, vtkIdType tuples, int components, int precision)
{
  vtkSmartPointer<vtkDataArray> array;
  array.TakeReference(vtkDataArray::CreateDataArray(IsSingle(precision) ? VTK_FLOAT : VTK_DOUBLE));
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  return array;
}

/// The values of an array made by NewArray, as the type it holds (float or double).
template <typename Real>
Real* ValuesOf(vtkDataArray* array)
{
  return static_cast<Real*>(array->GetVoidPointer(0));
}

} // namespace vtkGLSOutputPrecision

#endif
