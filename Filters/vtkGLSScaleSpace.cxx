#include "vtkGLSScaleSpace.h"

#include "vtkGLSArrayNames.h"

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include "gls/ScaleSpaceEngine.h" // gls::ScaleSampleSink

#include <cmath>
#include <type_traits>

vtkStandardNewMacro(vtkGLSScaleSpace);

namespace
{

/// Writes every sample straight into the output arrays (each point owns its own tuples: thread safe), in the
/// output precision T (double, or float when OutputPrecision is FLOAT).
template <typename T>
class ArraySink : public gls::ScaleSampleSink
{
public:
  std::size_t S = 0;
  T* Tau = nullptr;
  T* Eta = nullptr;
  T* Kappa = nullptr;
  T* Fitness = nullptr;
  T* DTau = nullptr;
  T* DEta = nullptr;
  T* DKappa = nullptr;
  int* Count = nullptr;

  static void put3(T* out, const gls::Vec3& v)
  {
    out[0] = static_cast<T>(v.x);
    out[1] = static_cast<T>(v.y);
    out[2] = static_cast<T>(v.z);
  }

  void consume(std::uint64_t id, const gls::ScaleSample* s, int) override
  {
    for (std::size_t k = 0; k < this->S; ++k)
    {
      const std::size_t o = id * this->S + k;
      if (this->Tau)
      {
        this->Tau[o] = static_cast<T>(s[k].tau);
      }
      if (this->Kappa)
      {
        this->Kappa[o] = static_cast<T>(s[k].kappa);
      }
      if (this->Fitness)
      {
        this->Fitness[o] = static_cast<T>(s[k].phi);
      }
      if (this->DTau)
      {
        this->DTau[o] = static_cast<T>(s[k].dtau);
        this->DKappa[o] = static_cast<T>(s[k].dkappa);
        put3(this->DEta + 3 * o, s[k].deta);
      }
      if (this->Eta)
      {
        put3(this->Eta + 3 * o, s[k].eta);
      }
      if (this->Count)
      {
        this->Count[o] = static_cast<int>(s[k].neighbors);
      }
    }
  }
};

/// Allocates the wanted arrays in precision T, binds them to a sink, runs it, and hands the arrays back.
template <typename T, typename ArrayType>
struct Outputs
{
  vtkSmartPointer<ArrayType> Tau, Eta, Kappa, Fitness, DTau, DEta, DKappa;
  ArraySink<T> Sink;

  static T* pointer(ArrayType* a) { return a ? a->GetPointer(0) : nullptr; }

  void bind()
  {
    this->Sink.Tau = pointer(this->Tau);
    this->Sink.Eta = pointer(this->Eta);
    this->Sink.Kappa = pointer(this->Kappa);
    this->Sink.Fitness = pointer(this->Fitness);
    this->Sink.DTau = pointer(this->DTau);
    this->Sink.DEta = pointer(this->DEta);
    this->Sink.DKappa = pointer(this->DKappa);
  }

  void addTo(vtkPointData* pd) const
  {
    for (ArrayType* a : { this->Tau.Get(), this->Eta.Get(), this->Kappa.Get(), this->Fitness.Get(),
           this->DTau.Get(), this->DEta.Get(), this->DKappa.Get() })
    {
      if (a)
      {
        pd->AddArray(a);
      }
    }
  }
};

} // namespace

vtkGLSScaleSpace::vtkGLSScaleSpace()
  : StoreTau(true)
  , StoreEta(true)
  , StoreKappa(true)
  , StoreFitness(true)
  , StoreDerivatives(true)
  , StoreNeighborCount(true)
  , OutputPrecision(DOUBLE)
{
}

vtkGLSScaleSpace::~vtkGLSScaleSpace() = default;

int vtkGLSScaleSpace::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!this->PrepareOutput(input, output))
  {
    return 0;
  }

  // Memory: every stored array is n x S (x 3 for the vectors) values of the output precision.
  const double valueBytes = this->OutputPrecision == FLOAT ? 4.0 : 8.0;
  const double valuesPerScale = (this->StoreTau ? 1 : 0) + (this->StoreKappa ? 1 : 0) + (this->StoreFitness ? 1 : 0) +
    (this->StoreEta ? 3 : 0) + (this->StoreDerivatives ? 5 : 0);
  OutputCost cost;
  cost.BytesPerPointScale = valuesPerScale * valueBytes + (this->StoreNeighborCount ? 4 : 0);
  cost.What = "storing every scale";
  cost.Advice = "Use fewer scales, OutputPrecision FLOAT (half the memory), turn off arrays you do not need "
                "(Store*), or use vtkGLSGeometricVariation / vtkGLSContinuousFeatures / "
                "vtkGLSMultiScaleDissimilarity directly on the points and normals: they compute in a fused pass that "
                "stores nothing per scale.";
  std::vector<double> scales;
  if (!this->PrepareScaleSamples(input, true, true, scales, cost))
  {
    return 0;
  }
  const vtkIdType n = input->GetNumberOfPoints();
  const int S = static_cast<int>(scales.size());

  vtkSmartPointer<vtkIntArray> count;
  if (this->StoreNeighborCount)
  {
    count = vtkSmartPointer<vtkIntArray>::New();
    count->SetName(vtkGLSArrayNames::NeighborCount);
    count->SetNumberOfComponents(S);
    count->SetNumberOfTuples(n);
    NameScaleComponents(count, scales, 1);
  }

  auto fill = [&](auto& outputs, auto makeArray) -> bool {
    outputs.Tau = makeArray(this->StoreTau, vtkGLSArrayNames::Tau, 1);
    outputs.Eta = makeArray(this->StoreEta, vtkGLSArrayNames::Eta, 3);
    outputs.Kappa = makeArray(this->StoreKappa, vtkGLSArrayNames::Kappa, 1);
    outputs.Fitness = makeArray(this->StoreFitness, vtkGLSArrayNames::Fitness, 1);
    outputs.DTau = makeArray(this->StoreDerivatives, vtkGLSArrayNames::DTau, 1);
    outputs.DEta = makeArray(this->StoreDerivatives, vtkGLSArrayNames::DEta, 3);
    outputs.DKappa = makeArray(this->StoreDerivatives, vtkGLSArrayNames::DKappa, 1);
    outputs.bind();
    outputs.Sink.S = scales.size();
    outputs.Sink.Count = count ? count->GetPointer(0) : nullptr;
    if (!this->RunScaleSamples(outputs.Sink))
    {
      return false; // aborted: the output is the input, without partial arrays
    }
    outputs.addTo(output->GetPointData());
    return true;
  };
  auto arrayMaker = [&](auto prototype) {
    using ArrayType = typename std::remove_pointer<decltype(prototype)>::type;
    return [&](bool wanted, const char* name, int perScale) -> vtkSmartPointer<ArrayType> {
      if (!wanted)
      {
        return nullptr;
      }
      auto a = vtkSmartPointer<ArrayType>::New();
      a->SetName(name);
      a->SetNumberOfComponents(S * perScale);
      a->SetNumberOfTuples(n);
      NameScaleComponents(a, scales, perScale);
      return a;
    };
  };
  bool completed;
  if (this->OutputPrecision == FLOAT)
  {
    Outputs<float, vtkFloatArray> outputs;
    completed = fill(outputs, arrayMaker(static_cast<vtkFloatArray*>(nullptr)));
  }
  else
  {
    Outputs<double, vtkDoubleArray> outputs;
    completed = fill(outputs, arrayMaker(static_cast<vtkDoubleArray*>(nullptr)));
  }
  if (!completed)
  {
    return 1;
  }
  if (count)
  {
    output->GetPointData()->AddArray(count);
  }
  StoreScales(output->GetFieldData(), scales);
  this->StoreBackend(output->GetFieldData());
  return 1;
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
  os << indent << "OutputPrecision: " << (this->OutputPrecision == FLOAT ? "Float" : "Double") << "\n";
}
