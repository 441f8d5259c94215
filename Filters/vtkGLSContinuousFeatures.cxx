#include "vtkGLSContinuousFeatures.h"

#include "vtkGLSArrayNames.h"

#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include "gls/Descriptors.h"
#include "gls/ScaleAnalysis.h"
#include "gls/ScaleSpaceEngine.h"

vtkStandardNewMacro(vtkGLSContinuousFeatures);

namespace
{

/// nu of one point from its samples, then f; nu lives in a per-thread buffer only.
class FeatureSink : public gls::ScaleSampleSink
{
public:
  const std::vector<double>* Scales = nullptr;
  gls::VariationWeights Weights;
  double Sigma = 0.1;
  gls::FeatureMeasure Measure = gls::FeatureMeasure::Scale;
  double* Feature = nullptr;
  std::vector<std::vector<double>> Nu; // one buffer per thread

  void consume(std::uint64_t id, const gls::ScaleSample* s, int thread) override
  {
    const std::size_t S = this->Scales->size();
    std::vector<double>& nu = this->Nu[thread];
    nu.resize(S);
    for (std::size_t k = 0; k < S; ++k)
    {
      nu[k] = gls::geometricVariation(s[k], (*this->Scales)[k], this->Weights);
    }
    this->Feature[id] =
      gls::continuousFeature(nu.data(), this->Scales->data(), static_cast<int>(S), this->Sigma, this->Measure);
  }
};

} // namespace

vtkGLSContinuousFeatures::vtkGLSContinuousFeatures()
  : Sigma(0.1)
  , FeatureMeasure(SCALE)
{
}

vtkGLSContinuousFeatures::~vtkGLSContinuousFeatures() = default;

int vtkGLSContinuousFeatures::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  PrepareOutput(input, output);
  const vtkIdType n = input->GetNumberOfPoints();
  if (n < 1)
  {
    vtkErrorMacro("The input has no points.");
    return 0;
  }
  vtkNew<vtkDoubleArray> feature;
  feature->SetName(vtkGLSArrayNames::Feature);
  feature->SetNumberOfTuples(n);
  const gls::FeatureMeasure measure = static_cast<gls::FeatureMeasure>(this->FeatureMeasure);

  // An upstream GLSGeometricVariation array: integrate it directly.
  std::vector<double> scales =
    this->ReuseInputScaleSpace ? ReadStoredScales(input->GetFieldData()) : std::vector<double>();
  vtkDataArray* storedNu = input->GetPointData()->GetArray(vtkGLSArrayNames::Variation);
  if (!scales.empty() && storedNu && storedNu->GetNumberOfComponents() == static_cast<int>(scales.size()) &&
    storedNu->GetNumberOfTuples() == n)
  {
    std::vector<double> nu(scales.size());
    for (vtkIdType i = 0; i < n; ++i)
    {
      storedNu->GetTuple(i, nu.data());
      feature->SetValue(i, gls::continuousFeature(
                             nu.data(), scales.data(), static_cast<int>(scales.size()), this->Sigma, measure));
      if (i % 65536 == 0 && this->ReportProgress(static_cast<double>(i) / n, 0.0, 1.0))
      {
        return 1; // aborted: no partial arrays
      }
    }
  }
  else
  {
    if (!this->PrepareScaleSamples(input, false, true, scales))
    {
      return 0;
    }
    FeatureSink sink;
    sink.Scales = &scales;
    sink.Weights = { this->WTau, this->WEta, this->WKappa };
    sink.Sigma = this->Sigma;
    sink.Measure = measure;
    sink.Feature = feature->GetPointer(0);
    sink.Nu.resize(static_cast<std::size_t>(gls::resolveThreadCount(this->NumberOfThreads)));
    if (!this->RunScaleSamples(sink))
    {
      return 1; // aborted: no partial arrays
    }
  }
  output->GetPointData()->AddArray(feature);
  output->GetPointData()->SetActiveScalars(vtkGLSArrayNames::Feature);
  StoreScales(output->GetFieldData(), scales);
  return 1;
}

void vtkGLSContinuousFeatures::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Sigma: " << this->Sigma << "\n";
  os << indent << "FeatureMeasure: " << (this->FeatureMeasure == SCALE ? "Scale" : "LogScale") << "\n";
}
