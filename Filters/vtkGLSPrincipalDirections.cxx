#include "vtkGLSPrincipalDirections.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSOutputPrecision.h"
#include "vtkGLSRun.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"

#include "gls/DirectionStability.h"
#include "gls/ScaleSpaceEngine.h"

#include <cmath>
#include <iterator>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkGLSPrincipalDirections);

namespace
{

/// An output array: its name and components (one value per component and point).
struct OutputArray
{
  const char* Name;
  int Components;
};

/// The steadiest direction's arrays, in the order of SteadiestValues.
constexpr OutputArray kSteadiestArrays[] = { { vtkGLSArrayNames::StableDirectionScale, 1 },
  { vtkGLSArrayNames::DirectionTurnRate, 1 }, { vtkGLSArrayNames::Anisotropy, 1 },
  { vtkGLSArrayNames::StableShapeIndex, 1 }, { vtkGLSArrayNames::StableDirection, 3 },
  { vtkGLSArrayNames::RidgeValley, 1 } };
constexpr int kSteadiestValues = 8;

/// DirectionScale's arrays, in the order of ChosenValues.
constexpr OutputArray kChosenArrays[] = { { vtkGLSArrayNames::K1AtScale, 1 }, { vtkGLSArrayNames::K2AtScale, 1 },
  { vtkGLSArrayNames::DirectionAtScale1, 3 }, { vtkGLSArrayNames::DirectionAtScale2, 3 } };
constexpr int kChosenValues = 8;

/// Reduces each point's principal curvatures over the scales to its steadiest direction (and copies those of the
/// chosen scale), into output arrays of Real (float or double: OutputPrecision).
template <typename Real>
class SteadiestDirectionSink : public gls::ScaleSampleSink
{
public:
  const std::vector<double>* Scales = nullptr;
  double Significance = gls::kSignificantAnisotropy;
  Real* Steadiest[std::size(kSteadiestArrays)] = {};
  /// DirectionScale's: the scale's index (-1: none) and its arrays.
  int ChosenScale = -1;
  Real* Chosen[std::size(kChosenArrays)] = {};

  void consumeCurvatures(std::uint64_t id, const gls::PrincipalCurvatures* c, int) override
  {
    const gls::StableDirection s = gls::steadiestDirection(
      c, this->Scales->data(), static_cast<int>(this->Scales->size()), this->Significance);
    const double steadiest[kSteadiestValues] = { s.scale, s.turnRate, s.anisotropy, s.shapeIndex, s.direction.x,
      s.direction.y, s.direction.z, s.ridgeValley };
    Write(kSteadiestArrays, this->Steadiest, steadiest, id);
    if (this->ChosenScale >= 0)
    {
      const gls::PrincipalCurvatures& k = c[this->ChosenScale];
      const double chosen[kChosenValues] = { k.k1, k.k2, k.d1.x, k.d1.y, k.d1.z, k.d2.x, k.d2.y, k.d2.z };
      Write(kChosenArrays, this->Chosen, chosen, id);
    }
  }

  void consume(std::uint64_t, const gls::ScaleSample*, int) override {}

private:
  /// Point id's values, one array after the other.
  template <std::size_t N>
  static void Write(const OutputArray (&arrays)[N], Real* const (&values)[N], const double* v, std::uint64_t id)
  {
    for (std::size_t a = 0; a < N; ++a)
    {
      const int m = arrays[a].Components;
      for (int j = 0; j < m; ++j)
      {
        values[a][m * id + j] = static_cast<Real>(*v++);
      }
    }
  }
};

/// The arrays of `list` for n points at `precision`.
template <std::size_t N>
std::vector<vtkSmartPointer<vtkDataArray>> NewArrays(const OutputArray (&list)[N], vtkIdType n, int precision)
{
  std::vector<vtkSmartPointer<vtkDataArray>> arrays;
  for (const OutputArray& a : list)
  {
    arrays.push_back(vtkGLSOutputPrecision::NewArray(a.Name, n, a.Components, precision));
  }
  return arrays;
}

/// The values written per point by the arrays of `list`.
template <std::size_t N>
constexpr int ValueCount(const OutputArray (&list)[N])
{
  int count = 0;
  for (const OutputArray& a : list)
  {
    count += a.Components;
  }
  return count;
}
static_assert(ValueCount(kSteadiestArrays) == kSteadiestValues && ValueCount(kChosenArrays) == kChosenValues,
  "the sink's values and the arrays agree");

} // namespace

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
  const auto reduce = [&](auto&& sink) {
    using Real = std::remove_pointer_t<std::decay_t<decltype(sink.Steadiest[0])>>;
    sink.Scales = &run.Scales;
    sink.Significance = this->AnisotropyThreshold;
    sink.ChosenScale = chosenScale;
    for (std::size_t a = 0; a < steadiest.size(); ++a)
    {
      sink.Steadiest[a] = vtkGLSOutputPrecision::ValuesOf<Real>(steadiest[a]);
    }
    for (std::size_t a = 0; a < chosen.size(); ++a)
    {
      sink.Chosen[a] = vtkGLSOutputPrecision::ValuesOf<Real>(chosen[a]);
    }
    return this->FeedSamples(run, sink);
  };
  if (!(vtkGLSOutputPrecision::IsSingle(precision) ? reduce(SteadiestDirectionSink<float>())
                                                    : reduce(SteadiestDirectionSink<double>())))
  {
    return ABORTED; // no partial arrays
  }
  vtkPointData* pd = run.Output->GetPointData();
  for (const auto& a : steadiest)
  {
    pd->AddArray(a);
  }
  pd->SetActiveVectors(vtkGLSArrayNames::StableDirection);
  pd->SetActiveScalars(vtkGLSArrayNames::RidgeValley);
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
