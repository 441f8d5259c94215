#include "vtkGLSContinuousFeatures.h"

#include "vtkGLSArrayNames.h"

#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include "gls/ScaleAnalysis.h"

#include <vector>

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
  const double sigma = this->Sigma;
  std::vector<double> scales;
  bool aborted = false;
  if (!this->ReduceVariationPerPoint(
        input,
        [sigma, measure](const double* nu, const std::vector<double>& t) {
          return gls::continuousFeature(nu, t.data(), static_cast<int>(t.size()), sigma, measure);
        },
        scales, feature->GetPointer(0), 1.0, aborted))
  {
    return 0;
  }
  if (aborted)
  {
    return 1; // no partial arrays
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
