#include "vtkGLSGeometricVariation.h"

#include "vtkGLSArrayNames.h"

#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include "gls/Descriptors.h"
#include "gls/ScaleAnalysis.h"
#include "gls/ScaleSpaceEngine.h"

#include <limits>

vtkStandardNewMacro(vtkGLSGeometricVariation);

namespace
{

class VariationSink : public gls::ScaleSampleSink
{
public:
  const std::vector<double>* Scales = nullptr;
  gls::VariationWeights Weights;
  int K = 3;
  double* Nu = nullptr;
  double* Pertinent = nullptr;
  int* Count = nullptr;

  void consume(std::uint64_t id, const gls::ScaleSample* s, int) override
  {
    const std::size_t S = this->Scales->size();
    double* nu = this->Nu + id * S;
    for (std::size_t k = 0; k < S; ++k)
    {
      nu[k] = gls::geometricVariation(s[k], (*this->Scales)[k], this->Weights);
    }
    double* out = this->Pertinent + id * static_cast<std::size_t>(this->K);
    const int found = gls::pertinentScales(nu, this->Scales->data(), static_cast<int>(S), this->K, out);
    for (int j = found; j < this->K; ++j)
    {
      out[j] = std::numeric_limits<double>::quiet_NaN();
    }
    this->Count[id] = found;
  }
};

} // namespace

vtkGLSGeometricVariation::vtkGLSGeometricVariation()
  : MaxNumberOfPertinentScales(3)
{
}

vtkGLSGeometricVariation::~vtkGLSGeometricVariation() = default;

int vtkGLSGeometricVariation::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!this->PrepareOutput(input, output))
  {
    return 0;
  }

  std::vector<double> scales;
  OutputCost cost;
  cost.BytesPerPointScale = 8.0; // GLSGeometricVariation, one double per point and scale
  cost.What = "the geometric variation of every scale";
  cost.Advice = "Use fewer scales, or vtkGLSContinuousFeatures, which integrates nu without storing it.";
  if (!this->PrepareScaleSamples(input, false, true, scales, cost))
  {
    return 0;
  }
  const vtkIdType n = input->GetNumberOfPoints();
  vtkNew<vtkDoubleArray> nu;
  nu->SetName(vtkGLSArrayNames::Variation);
  nu->SetNumberOfComponents(static_cast<int>(scales.size()));
  nu->SetNumberOfTuples(n);
  NameScaleComponents(nu, scales, 1);
  vtkNew<vtkDoubleArray> pertinent;
  pertinent->SetName(vtkGLSArrayNames::PertinentScales);
  pertinent->SetNumberOfComponents(this->MaxNumberOfPertinentScales);
  pertinent->SetNumberOfTuples(n);
  vtkNew<vtkIntArray> count;
  count->SetName(vtkGLSArrayNames::PertinentScaleCount);
  count->SetNumberOfTuples(n);

  VariationSink sink;
  sink.Scales = &scales;
  sink.Weights = { this->WTau, this->WEta, this->WKappa };
  sink.K = this->MaxNumberOfPertinentScales;
  sink.Nu = nu->GetPointer(0);
  sink.Pertinent = pertinent->GetPointer(0);
  sink.Count = count->GetPointer(0);
  if (!this->RunScaleSamples(sink))
  {
    return 1; // aborted: no partial arrays
  }
  output->GetPointData()->AddArray(nu);
  output->GetPointData()->AddArray(pertinent);
  output->GetPointData()->AddArray(count);
  StoreScales(output->GetFieldData(), scales);
  this->StoreBackend(output->GetFieldData());
  return 1;
}

void vtkGLSGeometricVariation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaxNumberOfPertinentScales: " << this->MaxNumberOfPertinentScales << "\n";
}
