#include "vtkGLSGeometricVariation.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSRun.h"

#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"

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
  : ReuseInputScaleSpace(true)
  , MaxNumberOfPertinentScales(3)
{
}

vtkGLSGeometricVariation::~vtkGLSGeometricVariation() = default;

vtkGLSScaleFilterBase::SampleRequest vtkGLSGeometricVariation::GetSampleRequest(const vtkGLSRun&) const
{
  SampleRequest request;
  request.Derivatives = true;
  request.MayReuseInput = this->ReuseInputScaleSpace;
  request.BytesPerPointScale = 8.0; // GLSGeometricVariation, one double per point and scale
  request.What = "the geometric variation of every scale";
  request.Advice = "Use fewer scales, or vtkGLSContinuousFeatures, which integrates nu without storing it.";
  return request;
}

int vtkGLSGeometricVariation::ComputeOutputs(vtkGLSRun& run)
{
  const std::vector<double>& scales = run.Scales;
  const vtkIdType n = run.Input->GetNumberOfPoints();
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
  sink.Weights = this->Weights();
  sink.K = this->MaxNumberOfPertinentScales;
  sink.Nu = nu->GetPointer(0);
  sink.Pertinent = pertinent->GetPointer(0);
  sink.Count = count->GetPointer(0);
  if (!this->FeedSamples(run, sink))
  {
    return ABORTED; // no partial arrays
  }
  vtkPointData* pd = run.Output->GetPointData();
  pd->AddArray(nu);
  pd->AddArray(pertinent);
  pd->AddArray(count);
  return COMPLETED;
}

void vtkGLSGeometricVariation::DescribeSettings(std::vector<SettingRange>& settings)
{
  this->Superclass::DescribeSettings(settings);
  settings.push_back({ "MaxNumberOfPertinentScales", static_cast<double>(this->MaxNumberOfPertinentScales), static_cast<double>(1), static_cast<double>(1000) });
}

void vtkGLSGeometricVariation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ReuseInputScaleSpace: " << this->ReuseInputScaleSpace << "\n";
  os << indent << "MaxNumberOfPertinentScales: " << this->MaxNumberOfPertinentScales << "\n";
}
