#include "vtkGLSAdaptiveBandwidth.h"

#include "vtkGLSArrayNames.h"

#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include "gls/AdaptiveBandwidth.h"
#include "gls/BandwidthSink.h"

#include <vector>

vtkStandardNewMacro(vtkGLSAdaptiveBandwidth);

vtkGLSAdaptiveBandwidth::vtkGLSAdaptiveBandwidth()
  : Threshold(0.01)
  , SmoothingRadius(0.01)
{
}

vtkGLSAdaptiveBandwidth::~vtkGLSAdaptiveBandwidth() = default;

int vtkGLSAdaptiveBandwidth::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!this->PrepareOutput(input, output))
  {
    return 0;
  }
  const vtkIdType n = input->GetNumberOfPoints();
  vtkNew<vtkDoubleArray> raw;
  raw->SetName(vtkGLSArrayNames::RawBandwidth);
  raw->SetNumberOfTuples(n);
  const double fitEnd = 0.9;

  // An upstream GLSGeometricVariation array: scan it directly.
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
      raw->SetValue(i, gls::rawBandwidth(nu.data(), scales.data(), static_cast<int>(scales.size()),
                         this->Threshold));
      if (i % 65536 == 0 && this->ReportProgress(static_cast<double>(i) / n, 0.0, fitEnd))
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
    gls::BandwidthSink sink(scales, gls::resolveThreadCount(this->NumberOfThreads),
      { this->WTau, this->WEta, this->WKappa }, this->Threshold, raw->GetPointer(0));
    if (!this->RunScaleSamples(sink, nullptr, 0.0, fitEnd))
    {
      return 1; // aborted: no partial arrays
    }
  }

  // Spatial regularization.
  std::vector<double> xyz(3 * static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    input->GetPoint(i, &xyz[3 * static_cast<std::size_t>(i)]);
  }
  vtkNew<vtkDoubleArray> bandwidth;
  bandwidth->SetName(vtkGLSArrayNames::Bandwidth);
  bandwidth->SetNumberOfTuples(n);
  gls::ParallelOptions parallel;
  parallel.threads = this->NumberOfThreads;
  parallel.progress = [this, fitEnd](double f) { return this->ReportProgress(f, fitEnd, 1.0); };
  const double radius = this->ToAbsoluteLength(input, this->SmoothingRadius);
  if (!gls::smoothBandwidth(
        xyz.data(), static_cast<std::size_t>(n), raw->GetPointer(0), radius, parallel, bandwidth->GetPointer(0)))
  {
    return 1; // aborted: no partial arrays
  }
  output->GetPointData()->AddArray(raw);
  output->GetPointData()->AddArray(bandwidth);
  output->GetPointData()->SetActiveScalars(vtkGLSArrayNames::Bandwidth);
  StoreScales(output->GetFieldData(), scales);
  this->StoreBackend(output->GetFieldData());
  return 1;
}

void vtkGLSAdaptiveBandwidth::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Threshold: " << this->Threshold << "\n";
  os << indent << "SmoothingRadius: " << this->SmoothingRadius << "\n";
}
