#include "vtkGLSScaleSpace.h"

#include "vtkGLSArrayNames.h"

#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include "gls/ScaleSpaceEngine.h"

#include <cmath>

vtkStandardNewMacro(vtkGLSScaleSpace);

namespace
{

/// Writes every sample straight into the output arrays (each point owns its own tuples: thread safe).
class ArraySink : public gls::ScaleSampleSink
{
public:
  std::size_t S = 0;
  double* Tau = nullptr;
  double* Eta = nullptr;
  double* Kappa = nullptr;
  double* Fitness = nullptr;
  double* DTau = nullptr;
  double* DEta = nullptr;
  double* DKappa = nullptr;
  int* Count = nullptr;

  void consume(std::uint64_t id, const gls::ScaleSample* s, int) override
  {
    for (std::size_t k = 0; k < this->S; ++k)
    {
      const std::size_t o = id * this->S + k;
      if (this->Tau)
      {
        this->Tau[o] = s[k].tau;
      }
      if (this->Kappa)
      {
        this->Kappa[o] = s[k].kappa;
      }
      if (this->Fitness)
      {
        this->Fitness[o] = s[k].phi;
      }
      if (this->DTau)
      {
        this->DTau[o] = s[k].dtau;
        this->DKappa[o] = s[k].dkappa;
        this->DEta[3 * o] = s[k].deta.x;
        this->DEta[3 * o + 1] = s[k].deta.y;
        this->DEta[3 * o + 2] = s[k].deta.z;
      }
      if (this->Eta)
      {
        this->Eta[3 * o] = s[k].eta.x;
        this->Eta[3 * o + 1] = s[k].eta.y;
        this->Eta[3 * o + 2] = s[k].eta.z;
      }
      if (this->Count)
      {
        this->Count[o] = static_cast<int>(s[k].neighbors);
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
{
}

vtkGLSScaleSpace::~vtkGLSScaleSpace() = default;

int vtkGLSScaleSpace::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  PrepareOutput(input, output);

  std::vector<double> points, normals;
  if (!this->GatherPointsAndNormals(input, points, normals))
  {
    return 0;
  }
  const std::vector<double> scales = this->ComputeAbsoluteScales(input);
  if (scales.empty())
  {
    return 0;
  }
  const vtkIdType n = input->GetNumberOfPoints();
  const int S = static_cast<int>(scales.size());

  auto makeArray = [&](bool wanted, const char* name, int perScale) -> vtkSmartPointer<vtkDoubleArray> {
    if (!wanted)
    {
      return nullptr;
    }
    auto a = vtkSmartPointer<vtkDoubleArray>::New();
    a->SetName(name);
    a->SetNumberOfComponents(S * perScale);
    a->SetNumberOfTuples(n);
    NameScaleComponents(a, scales, perScale);
    return a;
  };
  auto tau = makeArray(this->StoreTau, vtkGLSArrayNames::Tau, 1);
  auto eta = makeArray(this->StoreEta, vtkGLSArrayNames::Eta, 3);
  auto kappa = makeArray(this->StoreKappa, vtkGLSArrayNames::Kappa, 1);
  auto fitness = makeArray(this->StoreFitness, vtkGLSArrayNames::Fitness, 1);
  auto dtau = makeArray(this->StoreDerivatives, vtkGLSArrayNames::DTau, 1);
  auto deta = makeArray(this->StoreDerivatives, vtkGLSArrayNames::DEta, 3);
  auto dkappa = makeArray(this->StoreDerivatives, vtkGLSArrayNames::DKappa, 1);
  vtkSmartPointer<vtkIntArray> count;
  if (this->StoreNeighborCount)
  {
    count = vtkSmartPointer<vtkIntArray>::New();
    count->SetName(vtkGLSArrayNames::NeighborCount);
    count->SetNumberOfComponents(S);
    count->SetNumberOfTuples(n);
    NameScaleComponents(count, scales, 1);
  }

  ArraySink sink;
  sink.S = scales.size();
  sink.Tau = tau ? tau->GetPointer(0) : nullptr;
  sink.Eta = eta ? eta->GetPointer(0) : nullptr;
  sink.Kappa = kappa ? kappa->GetPointer(0) : nullptr;
  sink.Fitness = fitness ? fitness->GetPointer(0) : nullptr;
  sink.DTau = dtau ? dtau->GetPointer(0) : nullptr;
  sink.DEta = deta ? deta->GetPointer(0) : nullptr;
  sink.DKappa = dkappa ? dkappa->GetPointer(0) : nullptr;
  sink.Count = count ? count->GetPointer(0) : nullptr;

  gls::ScaleSpaceSettings settings;
  settings.scales = scales;
  settings.minNeighbors = this->ResolveMinimumNeighbors(points, normals);
  settings.parallel.threads = this->NumberOfThreads;
  settings.parallel.progress = [this](double f) { return this->ReportProgress(f, 0.0, 1.0); };
  gls::ScaleSpaceEngine engine(points.data(), normals.data(), points.size() / 3, settings);
  if (!this->RunEngine(engine, sink, nullptr, settings.parallel))
  {
    return 1; // aborted: the output is the input, without partial arrays
  }

  vtkPointData* pd = output->GetPointData();
  for (vtkDataArray* a : std::initializer_list<vtkDataArray*>{ tau, eta, kappa, fitness, dtau, deta, dkappa, count })
  {
    if (a)
    {
      pd->AddArray(a);
    }
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
}
