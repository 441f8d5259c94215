#include "vtkGLSPrincipalDirections.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSOutputPrecision.h"
#include "vtkGLSRun.h"

#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"

#include "gls/DirectionStability.h"
#include "gls/ScaleSpaceEngine.h"

vtkStandardNewMacro(vtkGLSPrincipalDirections);

namespace
{

/// Reduces each point's principal curvatures over the scales to its steadiest direction, into the output arrays.
class SteadiestDirectionSink : public gls::ScaleSampleSink
{
public:
  const std::vector<double>* Scales = nullptr;
  double Significance = gls::kSignificantAnisotropy;
  double* Scale = nullptr;
  double* TurnRate = nullptr;
  double* Anisotropy = nullptr;
  double* ShapeIndex = nullptr;
  double* Direction = nullptr;
  double* RidgeValley = nullptr;

  void consumeCurvatures(std::uint64_t id, const gls::PrincipalCurvatures* c, int) override
  {
    const gls::StableDirection s = gls::steadiestDirection(
      c, this->Scales->data(), static_cast<int>(this->Scales->size()), this->Significance);
    this->Scale[id] = s.scale;
    this->TurnRate[id] = s.turnRate;
    this->Anisotropy[id] = s.anisotropy;
    this->ShapeIndex[id] = s.shapeIndex;
    this->Direction[3 * id] = s.direction.x;
    this->Direction[3 * id + 1] = s.direction.y;
    this->Direction[3 * id + 2] = s.direction.z;
    this->RidgeValley[id] = s.ridgeValley;
  }

  void consume(std::uint64_t, const gls::ScaleSample*, int) override {}
};

/// A point array of doubles (the filter writes doubles: a handful per point).
vtkSmartPointer<vtkDataArray> NewPointArray(const char* name, int components, vtkIdType n)
{
  return vtkGLSOutputPrecision::NewArray(name, n, components, vtkAlgorithm::DOUBLE_PRECISION);
}

} // namespace

vtkGLSPrincipalDirections::vtkGLSPrincipalDirections()
  : ReuseInputScaleSpace(true)
  , AnisotropyThreshold(gls::kSignificantAnisotropy)
{
}

vtkGLSPrincipalDirections::~vtkGLSPrincipalDirections() = default;

vtkGLSScaleFilterBase::SampleRequest vtkGLSPrincipalDirections::GetSampleRequest(const vtkGLSRun&) const
{
  SampleRequest request;
  request.PrincipalCurvatures = true;
  request.MayReuseInput = this->ReuseInputScaleSpace;
  request.BytesPerPoint = 8.0 * 8.0; // six arrays, one of three components
  request.What = "the steadiest principal directions";
  request.Advice = "Use fewer points.";
  return request;
}

int vtkGLSPrincipalDirections::ComputeOutputs(vtkGLSRun& run)
{
  const vtkIdType n = run.Input->GetNumberOfPoints();
  const auto scale = NewPointArray(vtkGLSArrayNames::StableDirectionScale, 1, n);
  const auto turnRate = NewPointArray(vtkGLSArrayNames::DirectionTurnRate, 1, n);
  const auto anisotropy = NewPointArray(vtkGLSArrayNames::Anisotropy, 1, n);
  const auto shapeIndex = NewPointArray(vtkGLSArrayNames::StableShapeIndex, 1, n);
  const auto direction = NewPointArray(vtkGLSArrayNames::StableDirection, 3, n);
  const auto ridgeValley = NewPointArray(vtkGLSArrayNames::RidgeValley, 1, n);
  SteadiestDirectionSink sink;
  sink.Scales = &run.Scales;
  sink.Significance = this->AnisotropyThreshold;
  using vtkGLSOutputPrecision::ValuesOf;
  sink.Scale = ValuesOf<double>(scale);
  sink.TurnRate = ValuesOf<double>(turnRate);
  sink.Anisotropy = ValuesOf<double>(anisotropy);
  sink.ShapeIndex = ValuesOf<double>(shapeIndex);
  sink.Direction = ValuesOf<double>(direction);
  sink.RidgeValley = ValuesOf<double>(ridgeValley);
  if (!this->FeedSamples(run, sink))
  {
    return ABORTED; // no partial arrays
  }
  vtkPointData* pd = run.Output->GetPointData();
  for (vtkDataArray* a : { scale.Get(), turnRate.Get(), anisotropy.Get(), shapeIndex.Get() })
  {
    pd->AddArray(a);
  }
  pd->SetVectors(direction);
  pd->SetScalars(ridgeValley);
  return COMPLETED;
}

void vtkGLSPrincipalDirections::DescribeSettings(std::vector<SettingRange>& settings)
{
  this->Superclass::DescribeSettings(settings);
  settings.push_back({ "AnisotropyThreshold", this->AnisotropyThreshold, 0.01, 1.0 });
}

void vtkGLSPrincipalDirections::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ReuseInputScaleSpace: " << this->ReuseInputScaleSpace << "\n";
  os << indent << "AnisotropyThreshold: " << this->AnisotropyThreshold << "\n";
}
