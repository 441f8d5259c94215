#include "vtkGLSScaleProfiles.h"

#include "vtkGLSRun.h"

#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointSet.h"
#include "vtkTable.h"

#include "gls/Descriptors.h"
#include "gls/ScaleSpaceEngine.h"

#include <cstring>
#include <string>
#include <type_traits>
#include <unordered_map>

vtkStandardNewMacro(vtkGLSScaleProfiles);

namespace
{

/// Keeps the samples of the selected points (few points, many scales).
class ProfileSink : public gls::ScaleSampleSink
{
public:
  ProfileSink(const std::vector<std::uint64_t>& ids, std::size_t scales)
    : Ids(ids)
    , S(scales)
    , Samples(ids.size() * scales)
  {
  }
  void consume(std::uint64_t id, const gls::ScaleSample* s, int) override
  {
    for (std::size_t j = 0; j < this->Ids.size(); ++j)
    {
      if (this->Ids[j] == id)
      {
        std::copy(s, s + this->S, this->Samples.begin() + static_cast<long>(j * this->S));
      }
    }
  }
  const std::vector<std::uint64_t>& Ids;
  std::size_t S;
  std::vector<gls::ScaleSample> Samples;
};

/// The selected points of a run: this piece's indices of those it holds and their positions in PointIds.
struct SelectionState : vtkGLSRunState
{
  std::vector<std::uint64_t> Ids;
  std::vector<std::size_t> Slots;
};

} // namespace

vtkGLSScaleProfiles::vtkGLSScaleProfiles()
{
  this->NumberOfScales = 200;
}

vtkGLSScaleProfiles::~vtkGLSScaleProfiles() = default;

void vtkGLSScaleProfiles::AddPointId(vtkIdType id)
{
  this->PointIds.push_back(id);
  this->Modified();
}

void vtkGLSScaleProfiles::RemoveAllPointIds()
{
  if (!this->PointIds.empty())
  {
    this->PointIds.clear();
    this->Modified();
  }
}

vtkTable* vtkGLSScaleProfiles::GetOutputTable()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(0));
}

int vtkGLSScaleProfiles::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

int vtkGLSScaleProfiles::RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  return this->MakeDeclaredOutputs(outputVector);
}

int vtkGLSScaleProfiles::FillOutputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTable");
  return 1;
}

void vtkGLSScaleProfiles::PrepareOutputs(vtkGLSRun&) {}

bool vtkGLSScaleProfiles::CheckParameters(vtkGLSRun& run)
{
  if (!this->Superclass::CheckParameters(run))
  {
    return false;
  }
  if (this->PointIds.empty())
  {
    vtkErrorMacro("No point selected: AddPointId (PointIds in ParaView) names the points to profile.");
    return false;
  }
  auto state = std::make_unique<SelectionState>();
  if (!this->LocateSelectedPoints(run, state->Ids, state->Slots))
  {
    return false;
  }
  run.State = std::move(state);
  return true;
}

vtkGLSScaleFilterBase::SampleRequest vtkGLSScaleProfiles::GetSampleRequest(const vtkGLSRun& run) const
{
  SampleRequest request; // always its own fit, stores nothing per point and scale
  request.Only = &static_cast<const SelectionState&>(*run.State).Ids; // built around the selected points
  return request;
}

int vtkGLSScaleProfiles::ComputeOutputs(vtkGLSRun& run)
{
  const SelectionState& selection = static_cast<const SelectionState&>(*run.State);
  const std::vector<double>& scales = run.Scales;
  const vtkGLSDistributedCloud& dist = run.Distributed;
  ProfileSink sink(selection.Ids, scales.size());
  if (!dist.AllTrue(this->FeedSamples(run, sink, &selection.Ids)))
  {
    return ABORTED; // an empty table
  }
  std::vector<gls::ScaleSample> samples;
  if (!this->CollectSamples(run, sink.Samples, selection.Slots, scales.size(), samples))
  {
    return FAILED;
  }
  if (dist.GetRank() != 0)
  {
    return COMPLETED; // a distributed run: the table is on rank 0, the other ranks' tables are empty
  }

  vtkTable* output = vtkTable::GetData(run.OutputVector);
  const vtkIdType S = static_cast<vtkIdType>(scales.size());
  vtkNew<vtkDoubleArray> t;
  t->SetName("t");
  t->SetNumberOfTuples(S);
  for (vtkIdType k = 0; k < S; ++k)
  {
    t->SetValue(k, scales[static_cast<std::size_t>(k)]);
  }
  output->AddColumn(t);
  const gls::VariationWeights weights = this->Weights();
  for (std::size_t j = 0; j < this->PointIds.size(); ++j)
  {
    const std::string suffix = " (" + std::to_string(this->PointIds[j]) + ")";
    vtkNew<vtkDoubleArray> tau, kappa, phi, nu;
    tau->SetName(("tau/t" + suffix).c_str());
    kappa->SetName(("t*kappa" + suffix).c_str());
    phi->SetName(("phi" + suffix).c_str());
    nu->SetName(("nu" + suffix).c_str());
    for (vtkDoubleArray* a : { tau.Get(), kappa.Get(), phi.Get(), nu.Get() })
    {
      a->SetNumberOfTuples(S);
    }
    for (vtkIdType k = 0; k < S; ++k)
    {
      const gls::ScaleSample& s = samples[j * scales.size() + static_cast<std::size_t>(k)];
      const double tk = scales[static_cast<std::size_t>(k)];
      tau->SetValue(k, s.tau / tk);
      kappa->SetValue(k, tk * s.kappa);
      phi->SetValue(k, s.phi);
      nu->SetValue(k, gls::geometricVariation(s, tk, weights));
    }
    output->AddColumn(tau);
    output->AddColumn(kappa);
    output->AddColumn(phi);
    output->AddColumn(nu);
  }
  return COMPLETED;
}

bool vtkGLSScaleProfiles::LocateSelectedPoints(
  const vtkGLSRun& run, std::vector<std::uint64_t>& ids, std::vector<std::size_t>& slots)
{
  vtkPointSet* input = run.Input;
  const vtkIdType n = input->GetNumberOfPoints();
  const vtkGLSDistributedCloud& dist = run.Distributed;
  if (!dist.IsParallel())
  {
    for (std::size_t j = 0; j < this->PointIds.size(); ++j)
    {
      const vtkIdType id = this->PointIds[j];
      if (id < 0 || id >= n)
      {
        vtkErrorMacro("Point id " << id << " is out of range: the input has " << n << " points.");
        return false;
      }
      ids.push_back(static_cast<std::uint64_t>(id));
      slots.push_back(j);
    }
    return true;
  }
  // Global ids: every selected point is profiled by the rank that holds it.
  const std::vector<long long> global = dist.GlobalIds(input);
  std::unordered_map<long long, std::uint64_t> local;
  for (std::size_t i = 0; i < global.size(); ++i)
  {
    local.emplace(global[i], static_cast<std::uint64_t>(i));
  }
  for (std::size_t j = 0; j < this->PointIds.size(); ++j)
  {
    const auto found = local.find(static_cast<long long>(this->PointIds[j]));
    if (found != local.end())
    {
      ids.push_back(found->second);
      slots.push_back(j);
    }
  }
  if (dist.Sum(static_cast<double>(ids.size())) < static_cast<double>(this->PointIds.size()))
  {
    vtkErrorMacro("A selected point id is out of range: no piece holds a point with that global id (the GlobalIds "
                  "attribute, else the rank-order numbering of the pieces).");
    return false;
  }
  return true;
}

bool vtkGLSScaleProfiles::CollectSamples(const vtkGLSRun& run, const std::vector<gls::ScaleSample>& mine,
  const std::vector<std::size_t>& slots, std::size_t S, std::vector<gls::ScaleSample>& samples)
{
  samples.assign(this->PointIds.size() * S, gls::ScaleSample());
  const vtkGLSDistributedCloud& dist = run.Distributed;
  if (!dist.IsParallel())
  {
    for (std::size_t j = 0; j < slots.size(); ++j)
    {
      std::copy(mine.begin() + static_cast<long>(j * S), mine.begin() + static_cast<long>((j + 1) * S),
        samples.begin() + static_cast<long>(slots[j] * S));
    }
    return true;
  }
  // Rows of doubles: the slot, then the S samples' bytes.
  static_assert(std::is_trivially_copyable<gls::ScaleSample>::value, "sent as bytes");
  const std::size_t words = (sizeof(gls::ScaleSample) * S + sizeof(double) - 1) / sizeof(double);
  const int width = static_cast<int>(1 + words);
  std::vector<double> rows(slots.size() * static_cast<std::size_t>(width), 0.0);
  for (std::size_t j = 0; j < slots.size(); ++j)
  {
    double* row = &rows[j * static_cast<std::size_t>(width)];
    row[0] = static_cast<double>(slots[j]);
    std::memcpy(row + 1, &mine[j * S], sizeof(gls::ScaleSample) * S);
  }
  std::vector<double> all;
  std::vector<long long> counts;
  if (!dist.GatherRows(rows, width, 0, all, counts))
  {
    vtkErrorMacro("Gathering the profiles on rank 0 failed.");
    return false;
  }
  for (std::size_t r = 0; r < all.size() / static_cast<std::size_t>(width); ++r)
  {
    const double* row = &all[r * static_cast<std::size_t>(width)];
    std::memcpy(&samples[static_cast<std::size_t>(row[0]) * S], row + 1, sizeof(gls::ScaleSample) * S);
  }
  return true;
}

void vtkGLSScaleProfiles::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PointIds: " << this->PointIds.size() << "\n";
}
