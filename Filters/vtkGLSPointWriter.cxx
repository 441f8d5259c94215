#include "vtkGLSPointWriter.h"

#include "vtkGLSReaderParts.h"

#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkInformation.h"
#include "vtkPointSet.h"

#include <fstream>

vtkGLSPointWriter::vtkGLSPointWriter() = default;

vtkGLSPointWriter::~vtkGLSPointWriter() = default;

int vtkGLSPointWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

vtkPointSet* vtkGLSPointWriter::InputPositions(std::vector<double>& xyz)
{
  this->Description.clear();
  vtkPointSet* input = vtkPointSet::SafeDownCast(this->GetInput());
  const vtkIdType n = input ? input->GetNumberOfPoints() : 0;
  if (this->FileName.empty() || n == 0)
  {
    vtkErrorMacro(<< (this->FileName.empty() ? "No FileName set." : "The input has no points to write."));
    this->SetErrorCode(this->FileName.empty() ? vtkErrorCode::NoFileNameError : vtkErrorCode::UnknownError);
    return nullptr;
  }
  xyz.resize(3 * static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    input->GetPoint(i, &xyz[3 * static_cast<std::size_t>(i)]);
  }
  return input;
}

void vtkGLSPointWriter::PerPointValues(
  vtkDataArray* a, const float*& floats, const double*& doubles, std::vector<std::shared_ptr<void>>& kept)
{
  const bool isDouble = a->GetDataType() == VTK_DOUBLE;
  floats = isDouble ? nullptr : vtkGLSValuesAs<float>(a, 1.0, kept);
  doubles = isDouble ? vtkGLSValuesAs<double>(a, 1.0, kept) : nullptr;
}

bool vtkGLSPointWriter::WriteStream(
  const char* format, const std::function<bool(std::ostream&, std::string&)>& encode)
{
  std::ofstream out(this->FileName, std::ios::binary);
  std::string error;
  if (!out || !encode(out, error) || !out.flush())
  {
    vtkErrorMacro("Cannot write the " << format << " file '" << this->FileName << "': "
                                      << (error.empty() ? "it cannot be opened or written" : error) << ".");
    this->SetErrorCode(vtkErrorCode::GetLastSystemError() ? vtkErrorCode::GetLastSystemError()
                                                          : vtkErrorCode::CannotOpenFileError);
    return false;
  }
  return true;
}

void vtkGLSPointWriter::WarnPointsLeftOut(std::uint64_t leftOut, std::uint64_t n, const std::string& why)
{
  if (leftOut > 0)
  {
    vtkWarningMacro(<< leftOut << " of the " << n << " points have a non-finite coordinate and are not written to '"
                    << this->FileName << "' (" << why << ").");
  }
}

void vtkGLSPointWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Description: " << this->Description << "\n";
}
