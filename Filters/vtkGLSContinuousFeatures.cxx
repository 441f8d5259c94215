#include "vtkGLSContinuousFeatures.h"

#include "vtkGLSArrayNames.h"

#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include "gls/FeatureSink.h"

vtkStandardNewMacro(vtkGLSContinuousFeatures);


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
  if (!this->PrepareOutput(input, output))
  {
    return 0;
  }
  const vtkIdType n = input->GetNumberOfPoints();
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
    gls::ContinuousFeatureSink sink(scales, gls::resolveThreadCount(this->NumberOfThreads),
      { this->WTau, this->WEta, this->WKappa }, this->Sigma, measure, feature->GetPointer(0));
    if (!this->RunScaleSamples(sink))
    {
      return 1; // aborted: no partial arrays
    }
  }
  output->GetPointData()->AddArray(feature);
  output->GetPointData()->SetActiveScalars(vtkGLSArrayNames::Feature);
  StoreScales(output->GetFieldData(), scales);
  this->StoreBackend(output->GetFieldData());
  return 1;
}

void vtkGLSContinuousFeatures::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Sigma: " << this->Sigma << "\n";
  os << indent << "FeatureMeasure: " << (this->FeatureMeasure == SCALE ? "Scale" : "LogScale") << "\n";
}
