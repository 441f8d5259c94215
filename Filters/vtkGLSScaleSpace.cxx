#include "vtkGLSScaleSpace.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSDescriptors.h"
#include "vtkGLSRun.h"

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkSmartPointer.h"

#include "gls/ScaleSpaceEngine.h" // gls::ScaleSampleSink

#include <algorithm>
#include <limits>
#include <vector>

vtkStandardNewMacro(vtkGLSScaleSpace);

namespace
{

/// Writes every sample straight into the output arrays (each point owns its own tuples: thread safe): per stored
/// descriptor, its values in the output precision T (or int for the integer ones).
template <typename T>
class ArraySink : public gls::ScaleSampleSink
{
public:
  struct Column
  {
    const vtkGLSDescriptors::Descriptor* Descriptor;
    T* Values;     ///< floating-point descriptors
    int* Integers; ///< integer descriptors
  };
  struct CurvatureColumn
  {
    const vtkGLSDescriptors::CurvatureArray* Array;
    T* Values;
  };

  ArraySink(const std::vector<double>& scales, std::vector<Column> columns, std::vector<CurvatureColumn> curvatures,
    double* kappaMedian, int threads)
    : S(scales.size())
    , Scales(scales)
    , Columns(std::move(columns))
    , Curvatures(std::move(curvatures))
    , KappaMedian(kappaMedian)
    , Scratch(static_cast<std::size_t>(threads))
  {
  }

  void consumeCurvatures(std::uint64_t id, const gls::PrincipalCurvatures* c, int) override
  {
    for (const CurvatureColumn& column : this->Curvatures)
    {
      const int m = column.Array->Components;
      T* row = column.Values + id * this->S * static_cast<std::size_t>(m);
      for (std::size_t k = 0; k < this->S; ++k)
      {
        for (int j = 0; j < m; ++j)
        {
          row[k * static_cast<std::size_t>(m) + static_cast<std::size_t>(j)] =
            static_cast<T>(column.Array->Value(c[k], this->Scales[k], j));
        }
      }
    }
  }

  void consume(std::uint64_t id, const gls::ScaleSample* s, int thread) override
  {
    if (this->KappaMedian)
    {
      std::vector<double>& defined = this->Scratch[static_cast<std::size_t>(thread)];
      defined.clear();
      for (std::size_t k = 0; k < this->S; ++k)
      {
        if (s[k].valid)
        {
          defined.push_back(s[k].kappa);
        }
      }
      this->KappaMedian[id] = median(defined);
    }
    for (const Column& c : this->Columns)
    {
      const int m = c.Descriptor->Components;
      const std::size_t row = id * this->S * static_cast<std::size_t>(m);
      for (std::size_t k = 0; k < this->S; ++k)
      {
        for (int j = 0; j < m; ++j)
        {
          const std::size_t o = row + k * static_cast<std::size_t>(m) + static_cast<std::size_t>(j);
          const double v = vtkGLSDescriptors::Value(*c.Descriptor, s[k], j);
          if (c.Integers)
          {
            c.Integers[o] = static_cast<int>(v);
          }
          else
          {
            c.Values[o] = static_cast<T>(v);
          }
        }
      }
    }
  }

private:
  /// The median of the values (the mean of the two middle ones for an even count); NaN for none.
  static double median(std::vector<double>& v)
  {
    if (v.empty())
    {
      return std::numeric_limits<double>::quiet_NaN();
    }
    const std::size_t m = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(m), v.end());
    if (v.size() % 2 == 1)
    {
      return v[m];
    }
    const double upper = v[m];
    return 0.5 * (*std::max_element(v.begin(), v.begin() + static_cast<long>(m)) + upper);
  }

  std::size_t S;
  const std::vector<double>& Scales;
  std::vector<Column> Columns;
  std::vector<CurvatureColumn> Curvatures;
  double* KappaMedian;
  std::vector<std::vector<double>> Scratch;
};

/// Allocates the stored descriptors' arrays in precision T (ArrayType holds T), and the principal curvatures' when
/// `curvatures`, fills them from the run's samples, and adds them to the output in the tables' order. False if
/// aborted (nothing added).
template <typename T, typename ArrayType, typename Feed>
bool FillArrays(const std::vector<int>& stored, bool curvatures, const std::vector<double>& scales, vtkIdType n,
  vtkPointData* out, Feed feed, void (*nameComponents)(vtkDataArray*, const std::vector<double>&, int),
  vtkDoubleArray* kappaMedian, int threads)
{
  const int S = static_cast<int>(scales.size());
  std::vector<vtkSmartPointer<vtkDataArray>> arrays;
  // An array of `components` values per scale for every point, named, its components named, in the output's list.
  const auto addArray = [&](vtkSmartPointer<vtkDataArray> a, const char* name, int components) {
    a->SetNumberOfComponents(S * components);
    a->SetNumberOfTuples(n);
    a->SetName(name);
    nameComponents(a, scales, components);
    arrays.push_back(a);
  };
  std::vector<typename ArraySink<T>::Column> columns;
  for (int id : stored)
  {
    const vtkGLSDescriptors::Descriptor& d = vtkGLSDescriptors::Get(static_cast<vtkGLSDescriptors::Id>(id));
    typename ArraySink<T>::Column column{ &d, nullptr, nullptr };
    if (d.Integer)
    {
      auto ints = vtkSmartPointer<vtkIntArray>::New();
      addArray(ints, d.Name, d.Components);
      column.Integers = ints->GetPointer(0);
    }
    else
    {
      auto values = vtkSmartPointer<ArrayType>::New();
      addArray(values, d.Name, d.Components);
      column.Values = values->GetPointer(0);
    }
    columns.push_back(column);
  }
  std::vector<typename ArraySink<T>::CurvatureColumn> curvatureColumns;
  for (int id = 0; curvatures && id < vtkGLSDescriptors::NUMBER_OF_CURVATURE_ARRAYS; ++id)
  {
    const vtkGLSDescriptors::CurvatureArray& c =
      vtkGLSDescriptors::GetCurvature(static_cast<vtkGLSDescriptors::CurvatureId>(id));
    auto values = vtkSmartPointer<ArrayType>::New();
    addArray(values, c.Name, c.Components);
    curvatureColumns.push_back({ &c, values->GetPointer(0) });
  }
  ArraySink<T> sink(scales, std::move(columns), std::move(curvatureColumns),
    kappaMedian ? kappaMedian->GetPointer(0) : nullptr, threads);
  if (!feed(sink))
  {
    return false; // aborted: the output is the input, without partial arrays
  }
  for (vtkDataArray* a : arrays)
  {
    out->AddArray(a);
  }
  return true;
}

} // namespace

vtkGLSScaleSpace::vtkGLSScaleSpace()
  : StoreTau(true)
  , StoreEta(true)
  , StoreKappa(true)
  , StoreFitness(true)
  , StoreDerivatives(true)
  , StoreNeighborCount(true)
  , StorePrincipalCurvatures(false)
  , OutputPrecision(DOUBLE)
{
}

vtkGLSScaleSpace::~vtkGLSScaleSpace() = default;

bool vtkGLSScaleSpace::IsStored(int storeSwitch) const
{
  switch (storeSwitch)
  {
    case vtkGLSDescriptors::STORE_TAU:
      return this->StoreTau;
    case vtkGLSDescriptors::STORE_ETA:
      return this->StoreEta;
    case vtkGLSDescriptors::STORE_KAPPA:
      return this->StoreKappa;
    case vtkGLSDescriptors::STORE_FITNESS:
      return this->StoreFitness;
    case vtkGLSDescriptors::STORE_DERIVATIVES:
      return this->StoreDerivatives;
    case vtkGLSDescriptors::STORE_NEIGHBOR_COUNT:
      return this->StoreNeighborCount;
    default:
      return false;
  }
}

vtkGLSScaleFilterBase::SampleRequest vtkGLSScaleSpace::GetSampleRequest(const vtkGLSRun&) const
{
  // Memory: every stored array is n x S x components values of the output precision (int for the counts).
  const double valueBytes = this->OutputPrecision == FLOAT ? 4.0 : 8.0;
  SampleRequest request;
  for (int id = 0; id < vtkGLSDescriptors::NUMBER_OF_DESCRIPTORS; ++id)
  {
    const vtkGLSDescriptors::Descriptor& d = vtkGLSDescriptors::Get(static_cast<vtkGLSDescriptors::Id>(id));
    if (this->IsStored(d.StoredBy))
    {
      request.BytesPerPointScale += d.Components * (d.Integer ? 4.0 : valueBytes);
    }
  }
  for (int id = 0; this->StorePrincipalCurvatures && id < vtkGLSDescriptors::NUMBER_OF_CURVATURE_ARRAYS; ++id)
  {
    request.BytesPerPointScale +=
      vtkGLSDescriptors::GetCurvature(static_cast<vtkGLSDescriptors::CurvatureId>(id)).Components * valueBytes;
  }
  request.PrincipalCurvatures = this->StorePrincipalCurvatures;
  request.What = "storing every scale";
  request.Advice = "Use fewer scales, OutputPrecision FLOAT (half the memory), turn off arrays you do not need "
                   "(Store*), or use vtkGLSGeometricVariation / vtkGLSContinuousFeatures / "
                   "vtkGLSMultiScaleDissimilarity directly on the points and normals: they compute in a fused pass "
                   "that stores nothing per scale.";
  return request;
}

int vtkGLSScaleSpace::ComputeOutputs(vtkGLSRun& run)
{
  std::vector<int> stored;
  for (int id = 0; id < vtkGLSDescriptors::NUMBER_OF_DESCRIPTORS; ++id)
  {
    if (this->IsStored(vtkGLSDescriptors::Get(static_cast<vtkGLSDescriptors::Id>(id)).StoredBy))
    {
      stored.push_back(id);
    }
  }
  const vtkIdType n = run.Input->GetNumberOfPoints();
  const auto feed = [&](gls::ScaleSampleSink& sink) { return this->FeedSamples(run, sink); };
  vtkPointData* out = run.Output->GetPointData();
  // A per-point summary that colours well (a colour map of GLSKappa's magnitude is NaN wherever one scale is).
  vtkSmartPointer<vtkDoubleArray> median;
  if (this->StoreKappa)
  {
    median = vtkSmartPointer<vtkDoubleArray>::New();
    median->SetName(vtkGLSArrayNames::KappaMedian);
    median->SetNumberOfTuples(n);
  }
  const int threads = gls::resolveThreadCount(this->NumberOfThreads);
  const bool completed = this->OutputPrecision == FLOAT
    ? FillArrays<float, vtkFloatArray>(
        stored, this->StorePrincipalCurvatures, run.Scales, n, out, feed, &NameScaleComponents, median, threads)
    : FillArrays<double, vtkDoubleArray>(
        stored, this->StorePrincipalCurvatures, run.Scales, n, out, feed, &NameScaleComponents, median, threads);
  if (completed && median)
  {
    out->AddArray(median);
    out->SetActiveScalars(vtkGLSArrayNames::KappaMedian);
  }
  return completed ? COMPLETED : ABORTED;
}

void vtkGLSScaleSpace::DescribeSettings(std::vector<SettingRange>& settings)
{
  this->Superclass::DescribeSettings(settings);
  settings.push_back({ "OutputPrecision", static_cast<double>(this->OutputPrecision), static_cast<double>(DOUBLE), static_cast<double>(FLOAT) });
}

void vtkGLSScaleSpace::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "StoreTau: " << this->StoreTau << "\n";
  os << indent << "StoreEta: " << this->StoreEta << "\n";
  os << indent << "StoreKappa: " << this->StoreKappa << "\n";
  os << indent << "StoreFitness: " << this->StoreFitness << "\n";
  os << indent << "StoreDerivatives: " << this->StoreDerivatives << "\n";
  os << indent << "StoreNeighborCount: " << this->StoreNeighborCount << "\n";
  os << indent << "StorePrincipalCurvatures: " << this->StorePrincipalCurvatures << "\n";
  os << indent << "OutputPrecision: " << (this->OutputPrecision == FLOAT ? "Float" : "Double") << "\n";
}
