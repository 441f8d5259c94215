#include "vtkGLSVariationFilterBase.h"

#include "vtkGLSRun.h"

#include "vtkDataArray.h"
#include "vtkPolyData.h"

#include "gls/Descriptors.h"
#include "gls/VariationSink.h"

#include <cmath>
#include <vector>

vtkGLSVariationFilterBase::vtkGLSVariationFilterBase()
  : WTau(1.0)
  , WEta(1.0)
  , WKappa(1.0)
{
}

vtkGLSVariationFilterBase::~vtkGLSVariationFilterBase() = default;

bool vtkGLSVariationFilterBase::CheckParameters(vtkGLSRun&)
{
  const struct
  {
    const char* Name;
    double Value;
  } weights[] = { { "WTau", this->WTau }, { "WEta", this->WEta }, { "WKappa", this->WKappa } };
  for (const auto& w : weights)
  {
    if (!(w.Value >= 0.0) || !std::isfinite(w.Value))
    {
      vtkErrorMacro(<< w.Name << " must be a finite weight >= 0 (it is " << w.Value << ").");
      return false;
    }
  }
  if (!(this->WTau + this->WEta + this->WKappa > 0.0))
  {
    vtkErrorMacro("WTau, WEta and WKappa are all 0: nu would be 0 everywhere; make one of them positive.");
    return false;
  }
  return true;
}

gls::VariationWeights vtkGLSVariationFilterBase::Weights() const
{
  return { this->WTau, this->WEta, this->WKappa };
}

vtkGLSScaleFilterBase::SampleRequest vtkGLSVariationFilterBase::VariationRequest(bool mayReuseInput)
{
  SampleRequest request;
  request.Derivatives = true;
  request.VariationWillDo = true;
  request.MayReuseInput = mayReuseInput;
  return request;
}

bool vtkGLSVariationFilterBase::ReduceVariation(
  vtkGLSRun& run, const VariationReducer& reduce, double* out, double progressEnd)
{
  if (run.StoredVariation)
  {
    const vtkIdType n = run.Input->GetNumberOfPoints();
    std::vector<double> nu(run.Scales.size());
    for (vtkIdType i = 0; i < n; ++i)
    {
      run.StoredVariation->GetTuple(i, nu.data());
      out[i] = reduce(nu.data());
      if (i % 65536 == 0 && this->ReportProgress(static_cast<double>(i) / n, 0.0, progressEnd))
      {
        return false;
      }
    }
    return true;
  }
  gls::VariationReductionSink sink(
    run.Scales, gls::resolveThreadCount(this->NumberOfThreads), this->Weights(), reduce, out);
  return this->FeedSamples(run, sink, nullptr, 0.0, progressEnd);
}

void vtkGLSVariationFilterBase::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "WTau, WEta, WKappa: " << this->WTau << ", " << this->WEta << ", " << this->WKappa << "\n";
}
