// The arrays of each point's steadiest principal direction (gls::StableDirection) and their writer, shared by the
// filters that reduce the principal curvatures over the scales as they are computed (private to the module): GLS
// Principal Directions, and GLS Continuous Features with DirectionSummary (the same arrays from its fused pass).
#ifndef vtkGLSSteadiestDirections_h
#define vtkGLSSteadiestDirections_h

#include "vtkGLSArrayNames.h"
#include "vtkGLSOutputPrecision.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include "gls/DirectionStability.h"
#include "gls/ScaleSpaceEngine.h"

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <vector>

namespace vtkGLSSteadiestDirections
{

/// An output array: its name and components (one value per component and point).
struct OutputArray
{
  const char* Name;
  int Components;
};

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

/// The steadiest direction's arrays, in the order of the values SteadiestDirectionSink writes.
constexpr OutputArray kSteadiestArrays[] = { { vtkGLSArrayNames::StableDirectionScale, 1 },
  { vtkGLSArrayNames::DirectionTurnRate, 1 }, { vtkGLSArrayNames::Anisotropy, 1 },
  { vtkGLSArrayNames::StableShapeIndex, 1 }, { vtkGLSArrayNames::StableDirection, 3 },
  { vtkGLSArrayNames::RidgeValley, 1 } };
constexpr int kSteadiestValues = ValueCount(kSteadiestArrays);

/// One chosen scale's arrays (GLS Principal Directions' DirectionScale), in the order of the values written.
constexpr OutputArray kChosenArrays[] = { { vtkGLSArrayNames::K1AtScale, 1 }, { vtkGLSArrayNames::K2AtScale, 1 },
  { vtkGLSArrayNames::DirectionAtScale1, 3 }, { vtkGLSArrayNames::DirectionAtScale2, 3 } };
constexpr int kChosenValues = ValueCount(kChosenArrays);

/// The arrays of `list` for n points at `precision` (vtkGLSOutputPrecision).
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

/// Reduces each point's principal curvatures over the scales to its steadiest direction (and copies those of a
/// chosen scale), into output arrays of Real (float or double: the arrays' precision). Ignores the sphere samples.
template <typename Real>
class SteadiestDirectionSink : public gls::ScaleSampleSink
{
public:
  /// The increasing scales (length), the significance of gls::steadiestDirection, the index of the chosen scale
  /// (-1: none) and the arrays (NewArrays of kSteadiestArrays, and of kChosenArrays when a scale is chosen).
  SteadiestDirectionSink(const std::vector<double>& scales, double significance, int chosenScale,
    const std::vector<vtkSmartPointer<vtkDataArray>>& steadiest,
    const std::vector<vtkSmartPointer<vtkDataArray>>& chosen)
    : Scales(scales)
    , Significance(significance)
    , ChosenScale(chosenScale)
  {
    for (std::size_t a = 0; a < std::size(kSteadiestArrays); ++a)
    {
      this->Steadiest[a] = vtkGLSOutputPrecision::ValuesOf<Real>(steadiest[a]);
    }
    for (std::size_t a = 0; a < chosen.size() && a < std::size(kChosenArrays); ++a)
    {
      this->Chosen[a] = vtkGLSOutputPrecision::ValuesOf<Real>(chosen[a]);
    }
  }

  void consumeCurvatures(std::uint64_t id, const gls::PrincipalCurvatures* c, int) override
  {
    const gls::StableDirection s =
      gls::steadiestDirection(c, this->Scales.data(), static_cast<int>(this->Scales.size()), this->Significance);
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

  const std::vector<double>& Scales;
  double Significance;
  int ChosenScale;
  Real* Steadiest[std::size(kSteadiestArrays)] = {};
  Real* Chosen[std::size(kChosenArrays)] = {};
};

/// Runs `feed` (a callable taking a gls::ScaleSampleSink&) with the sink of the arrays' precision: float32 arrays
/// get a SteadiestDirectionSink<float>, doubles one of double. Returns what feed returns (false: aborted).
template <typename Feed>
bool WithSink(int precision, const std::vector<double>& scales, double significance, int chosenScale,
  const std::vector<vtkSmartPointer<vtkDataArray>>& steadiest,
  const std::vector<vtkSmartPointer<vtkDataArray>>& chosen, const Feed& feed)
{
  if (vtkGLSOutputPrecision::IsSingle(precision))
  {
    SteadiestDirectionSink<float> sink(scales, significance, chosenScale, steadiest, chosen);
    return feed(sink);
  }
  SteadiestDirectionSink<double> sink(scales, significance, chosenScale, steadiest, chosen);
  return feed(sink);
}

/// Adds the steadiest direction's arrays to `pd`, GLSStableDirection as the active vectors and GLSRidgeValley as
/// the active scalars when `active`.
inline void AddTo(vtkPointData* pd, const std::vector<vtkSmartPointer<vtkDataArray>>& steadiest, bool active)
{
  for (const auto& a : steadiest)
  {
    pd->AddArray(a);
  }
  if (active)
  {
    pd->SetActiveVectors(vtkGLSArrayNames::StableDirection);
    pd->SetActiveScalars(vtkGLSArrayNames::RidgeValley);
  }
}

} // namespace vtkGLSSteadiestDirections

#endif
