#include "vtkGLSPrincipalDirections.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSOutputPrecision.h"
#include "vtkGLSRun.h"
#include "vtkGLSSteadiestDirections.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"

#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkGLSPrincipalDirections);

using namespace vtkGLSSteadiestDirections;

vtkGLSPrincipalDirections::vtkGLSPrincipalDirections()
  : ReuseInputScaleSpace(true)
  , AnisotropyThreshold(gls::kSignificantAnisotropy)
  , DirectionScale(0.0)
  , OutputPrecision(vtkAlgorithm::DOUBLE_PRECISION)
{
}

vtkGLSPrincipalDirections::~vtkGLSPrincipalDirections() = default;

vtkGLSScaleFilterBase::SampleRequest vtkGLSPrincipalDirections::GetSampleRequest(const vtkGLSRun&) const
{
  SampleRequest request;
  request.PrincipalCurvatures = true;
  request.MayReuseInput = this->ReuseInputScaleSpace;
  request.BytesPerPoint = vtkGLSOutputPrecision::ValueBytes(this->OutputPrecision) *
    (kSteadiestValues + (this->DirectionScale > 0.0 ? kChosenValues : 0));
  request.What = "the steadiest principal directions";
  request.Advice = "Use fewer points.";
  return request;
}

int vtkGLSPrincipalDirections::ChosenScaleIndex(const vtkGLSRun& run)
{
  if (this->DirectionScale <= 0.0)
  {
    return -1;
  }
  const std::vector<double>& scales = run.Scales;
  const double wanted = this->ToAbsoluteLength(run, this->DirectionScale);
  const double slack = 1e-9; // relative: a DirectionScale equal to MinScale or MaxScale, rounded
  if (!(wanted >= scales.front() * (1.0 - slack) && wanted <= scales.back() * (1.0 + slack)))
  {
    vtkErrorMacro("DirectionScale " << this->DirectionScale << " (absolute: " << wanted
                                    << ") lies outside the analysed scales, [" << scales.front() << ", "
                                    << scales.back() << "] (absolute); choose one within them, or 0 for none.");
    return -2;
  }
  int nearest = 0;
  for (int k = 1; k < static_cast<int>(scales.size()); ++k)
  {
    if (std::abs(std::log(scales[k] / wanted)) < std::abs(std::log(scales[nearest] / wanted)))
    {
      nearest = k;
    }
  }
  return nearest;
}

int vtkGLSPrincipalDirections::ComputeOutputs(vtkGLSRun& run)
{
  const int chosenScale = this->ChosenScaleIndex(run);
  if (chosenScale == -2)
  {
    return FAILED;
  }
  const vtkIdType n = run.Input->GetNumberOfPoints();
  const int precision = this->OutputPrecision;
  const auto steadiest = NewArrays(kSteadiestArrays, n, precision);
  const auto chosen =
    chosenScale >= 0 ? NewArrays(kChosenArrays, n, precision) : std::vector<vtkSmartPointer<vtkDataArray>>();
  if (!WithSink(precision, run.Scales, this->AnisotropyThreshold, chosenScale, steadiest, chosen,
        [&](gls::ScaleSampleSink& sink) { return this->FeedSamples(run, sink); }))
  {
    return ABORTED; // no partial arrays
  }
  vtkPointData* pd = run.Output->GetPointData();
  AddTo(pd, steadiest, true);
  if (chosenScale >= 0)
  {
    for (const auto& a : chosen)
    {
      pd->AddArray(a);
    }
    pd->SetActiveVectors(vtkGLSArrayNames::DirectionAtScale1); // the glyphs show the chosen scale's d1
    vtkNew<vtkDoubleArray> scale;
    scale->SetName(vtkGLSArrayNames::DirectionScale);
    scale->InsertNextValue(run.Scales[chosenScale]);
    run.Output->GetFieldData()->AddArray(scale);
  }
  return COMPLETED;
}

void vtkGLSPrincipalDirections::DescribeSettings(std::vector<SettingRange>& settings)
{
  this->Superclass::DescribeSettings(settings);
  settings.push_back({ "AnisotropyThreshold", this->AnisotropyThreshold, 0.01, 1.0 });
  settings.push_back({ "DirectionScale", this->DirectionScale, 0.0, VTK_DOUBLE_MAX });
  settings.push_back({ "OutputPrecision", static_cast<double>(this->OutputPrecision),
    static_cast<double>(vtkAlgorithm::SINGLE_PRECISION), static_cast<double>(vtkAlgorithm::DOUBLE_PRECISION) });
}

void vtkGLSPrincipalDirections::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ReuseInputScaleSpace: " << this->ReuseInputScaleSpace << "\n";
  os << indent << "AnisotropyThreshold: " << this->AnisotropyThreshold << "\n";
  os << indent << "DirectionScale: " << this->DirectionScale << "\n";
  os << indent << "OutputPrecision: " << vtkGLSOutputPrecision::Name(this->OutputPrecision) << "\n";
}
