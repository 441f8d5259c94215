#include "vtkGLSContinuousFeatures.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSRun.h"

#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include "gls/ScaleAnalysis.h"

#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkGLSContinuousFeatures);

vtkGLSContinuousFeatures::vtkGLSContinuousFeatures()
  : ReuseInputScaleSpace(true)
  , Sigma(0.1)
  , FeatureMeasure(SCALE)
{
}

vtkGLSContinuousFeatures::~vtkGLSContinuousFeatures() = default;

bool vtkGLSContinuousFeatures::CheckParameters(vtkGLSRun&)
{
  if (!(this->Sigma > 0.0) || !std::isfinite(this->Sigma))
  {
    vtkErrorMacro("Sigma must be a positive finite number (it is " << this->Sigma
                                                                  << "): it is the scale of tanh(nu / Sigma).");
    return false;
  }
  return true;
}

vtkGLSScaleFilterBase::SampleRequest vtkGLSContinuousFeatures::GetSampleRequest(const vtkGLSRun&) const
{
  return VariationRequest(this->ReuseInputScaleSpace);
}

int vtkGLSContinuousFeatures::ComputeOutputs(vtkGLSRun& run)
{
  vtkNew<vtkDoubleArray> feature;
  feature->SetName(vtkGLSArrayNames::Feature);
  feature->SetNumberOfTuples(run.Input->GetNumberOfPoints());
  const gls::FeatureMeasure measure = static_cast<gls::FeatureMeasure>(this->FeatureMeasure);
  const double sigma = this->Sigma;
  const std::vector<double>& t = run.Scales;
  if (!this->ReduceVariation(
        run,
        [sigma, measure, &t](const double* nu) {
          return gls::continuousFeature(nu, t.data(), static_cast<int>(t.size()), sigma, measure);
        },
        feature->GetPointer(0), 1.0))
  {
    return ABORTED; // no partial arrays
  }
  run.Output->GetPointData()->AddArray(feature);
  run.Output->GetPointData()->SetActiveScalars(vtkGLSArrayNames::Feature);
  return COMPLETED;
}

void vtkGLSContinuousFeatures::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ReuseInputScaleSpace: " << this->ReuseInputScaleSpace << "\n";
  os << indent << "Sigma: " << this->Sigma << "\n";
  os << indent << "FeatureMeasure: " << (this->FeatureMeasure == SCALE ? "Scale" : "LogScale") << "\n";
}
