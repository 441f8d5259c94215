/**
 * @class   vtkGLSPointWriter
 * @brief   What the GLS file writers (vtkGLSLasWriter, vtkGLSPlyWriter) share: a point set in, a file name, the
 *          description of the last write, and the steps around the format's own encoder.
 *
 * A subclass's WriteData takes the positions (InputPositions: refused with an error when there is no file name or
 * no point), hands plain arrays to the core's encoder (PerPointValues: a numeric array as floats, or doubles when it
 * is double), writes the stream (WriteStream: an error naming the file and the encoder's reason, the error code the
 * system's), and says what it wrote in Description.
 */
#ifndef vtkGLSPointWriter_h
#define vtkGLSPointWriter_h

#include "vtkGLSFiltersModule.h"
#include "vtkWriter.h"

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

class vtkDataArray;
class vtkPointSet;

class VTKGLSFILTERS_EXPORT vtkGLSPointWriter : public vtkWriter
{
public:
  vtkTypeMacro(vtkGLSPointWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to write.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /// What the last write did (the format's own words, e.g. "LAS 1.4, point format 6, 35947 points, ..."); empty
  /// before a write and after a failed one.
  vtkGetCharFromStdStringMacro(Description);

protected:
  vtkGLSPointWriter();
  ~vtkGLSPointWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  /// The input and its positions (3 doubles a point) into xyz; null, with an error, when there is no file name or
  /// no point to write.
  vtkPointSet* InputPositions(std::vector<double>& xyz);

  /// Points `floats` or `doubles` (whichever the array's type gives: doubles for a double array, floats otherwise)
  /// at the array's values, the other at null; a copy converted where needed is held in `kept`.
  static void PerPointValues(
    vtkDataArray* a, const float*& floats, const double*& doubles, std::vector<std::shared_ptr<void>>& kept);

  /// Opens FileName and runs `encode` on it; false with an error naming the file and why (`encode`'s reason, or the
  /// system's) and the error code set.
  bool WriteStream(const char* format, const std::function<bool(std::ostream&, std::string&)>& encode);

  /// One warning: `leftOut` of the n points have a non-finite coordinate and were not written, and `why`.
  void WarnPointsLeftOut(std::uint64_t leftOut, std::uint64_t n, const std::string& why);

  std::string FileName;
  std::string Description;

private:
  vtkGLSPointWriter(const vtkGLSPointWriter&) = delete;
  void operator=(const vtkGLSPointWriter&) = delete;
};


#endif
