#include "vtkGLSMultiScaleDissimilarity.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSRun.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkMath.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkUnsignedCharArray.h"

#include "gls/ScaleAnalysis.h"
#include "gls/ScaleSpaceEngine.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

vtkStandardNewMacro(vtkGLSMultiScaleDissimilarity);

namespace
{

class CaptureSink : public gls::ScaleSampleSink
{
public:
  std::vector<gls::ScaleSample> Samples;
  void consume(std::uint64_t, const gls::ScaleSample* s, int) override
  {
    this->Samples.assign(s, s + this->Samples.size());
  }
};

class DissimilaritySink : public gls::ScaleSampleSink
{
public:
  const std::vector<double>* Scales = nullptr;
  const std::vector<double>* Prior = nullptr;
  const gls::ScaleSample* Query = nullptr;
  double Threshold = 0.0;
  double* Delta = nullptr;
  unsigned char* Similar = nullptr;

  void consume(std::uint64_t id, const gls::ScaleSample* s, int) override
  {
    const double d = gls::multiScaleDissimilarity(this->Query, s, *this->Scales, *this->Prior);
    this->Delta[id] = d;
    this->Similar[id] = d < this->Threshold ? 1 : 0;
  }
};

/// The query point of a run: this piece's index of it (-1 on the other ranks), its global id, its owner rank.
struct QueryState : vtkGLSRunState
{
  vtkIdType Index = -1;
  long long GlobalId = -1;
  int Owner = 0;
};

} // namespace

struct vtkGLSMultiScaleDissimilarity::CompositeQuery
{
  std::size_t Block = 0;     ///< the block (leaf index) holding the query
  long long Offset = 0;      ///< points of the blocks before it
  vtkIdType Local = -1;      ///< the query's id in its block (-1: by coordinates)
  long long Flat = -1;       ///< the query's id over all the blocks
  bool Known = false;        ///< the query's block ran: Samples and Scales hold its descriptors
  std::vector<gls::ScaleSample> Samples;
  std::vector<double> Scales;
};

vtkGLSMultiScaleDissimilarity::vtkGLSMultiScaleDissimilarity()
  : ReuseInputScaleSpace(true)
  , QueryPointId(0)
  , QueryPoint{ 0.0, 0.0, 0.0 }
  , UseQueryPointCoordinates(false)
  , PriorMinScale(0.0)
  , PriorMaxScale(0.0)
  , PriorShape(BOX)
  , Threshold(0.01)
{
}

vtkGLSMultiScaleDissimilarity::~vtkGLSMultiScaleDissimilarity() = default;

bool vtkGLSMultiScaleDissimilarity::CheckParameters(vtkGLSRun& run)
{
  if (!(this->PriorMinScale >= 0.0) || !(this->PriorMaxScale >= 0.0) || !std::isfinite(this->PriorMinScale) ||
    !std::isfinite(this->PriorMaxScale))
  {
    vtkErrorMacro("Invalid scale prior: PriorMinScale " << this->PriorMinScale << " and PriorMaxScale "
                                                        << this->PriorMaxScale
                                                        << " must be finite and >= 0 (PriorMaxScale 0: no upper "
                                                           "limit).");
    return false;
  }
  if (this->PriorMaxScale > 0.0 && this->PriorMinScale > this->PriorMaxScale)
  {
    vtkErrorMacro("Invalid scale prior: PriorMinScale " << this->PriorMinScale << " is above PriorMaxScale "
                                                        << this->PriorMaxScale << ".");
    return false;
  }
  vtkPointSet* input = run.Input;
  const vtkIdType n = input->GetNumberOfPoints();
  const vtkGLSDistributedCloud& dist = run.Distributed;
  auto state = std::make_unique<QueryState>();
  if (this->Composite && this->Composite->Known)
  {
    state->GlobalId = this->Composite->Flat; // another block: compared with the query of the first one run
    run.State = std::move(state);
    return true;
  }
  const vtkIdType wanted = this->Composite ? this->Composite->Local : this->QueryPointId;
  const bool byCoordinates = this->UseQueryPointCoordinates;
  if (!byCoordinates && wanted < 0)
  {
    vtkErrorMacro("QueryPointId must be a point id, >= 0 (it is " << this->QueryPointId << ").");
    return false;
  }
  // The query point (in a distributed run, this piece's index of it, -1 on the other ranks).
  vtkIdType query = wanted;
  double best = std::numeric_limits<double>::infinity();
  const double* q = this->QueryPoint;
  if (byCoordinates && !(std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2])))
  {
    vtkErrorMacro("QueryPoint (" << q[0] << ", " << q[1] << ", " << q[2] << ") must be finite (UseQueryPointCoordinates).");
    return false;
  }
  if (byCoordinates)
  {
    query = -1;
    for (vtkIdType i = 0; i < n; ++i)
    {
      double p[3];
      input->GetPoint(i, p);
      const double d2 = this->QueryDistance2(p);
      if (d2 < best)
      {
        best = d2;
        query = i;
      }
    }
    if (query < 0 && !dist.IsParallel())
    {
      vtkErrorMacro("No input point with finite coordinates to snap the query point to.");
      return false;
    }
    if (!dist.IsParallel() && !this->CheckQueryPointIsNear(run, best))
    {
      return false;
    }
  }
  long long queryGlobalId = query;
  if (dist.IsParallel() && !this->LocateDistributedQuery(run, wanted, best, query, queryGlobalId, state->Owner))
  {
    return false;
  }
  if (!dist.IsParallel() && query >= n)
  {
    vtkErrorMacro("QueryPointId " << query << " is out of range: the input has " << n << " points.");
    return false;
  }
  state->Index = query;
  state->GlobalId = this->Composite ? this->Composite->Offset + queryGlobalId : queryGlobalId;
  run.State = std::move(state);
  return true;
}

bool vtkGLSMultiScaleDissimilarity::BeginComposite(
  const std::vector<vtkSmartPointer<vtkPointSet>>& blocks, double, std::vector<std::size_t>& order)
{
  const vtkGLSDistributedCloud dist(this->Controller);
  auto composite = std::make_unique<CompositeQuery>();
  std::vector<long long> offsets(blocks.size() + 1, 0);
  for (std::size_t b = 0; b < blocks.size(); ++b)
  {
    offsets[b + 1] = offsets[b] + static_cast<long long>(dist.Sum(static_cast<double>(blocks[b]->GetNumberOfPoints())));
  }
  if (this->UseQueryPointCoordinates)
  {
    // The block holding the nearest point of all (the first such block on a tie).
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < blocks.size(); ++b)
    {
      double mine = std::numeric_limits<double>::infinity();
      for (vtkIdType i = 0; i < blocks[b]->GetNumberOfPoints(); ++i)
      {
        double p[3];
        blocks[b]->GetPoint(i, p);
        mine = std::min(mine, this->QueryDistance2(p));
      }
      mine = dist.Min(mine);
      if (mine < best)
      {
        best = mine;
        composite->Block = b;
      }
    }
    if (!(best < std::numeric_limits<double>::infinity()))
    {
      vtkErrorMacro("No input point with finite coordinates to snap the query point to.");
      return false;
    }
  }
  else
  {
    if (this->QueryPointId < 0 || this->QueryPointId >= offsets.back())
    {
      vtkErrorMacro("QueryPointId " << this->QueryPointId << " is out of range: the " << blocks.size()
                                    << " blocks have " << offsets.back() << " points in all (QueryPointId counts "
                                       "them block after block).");
      return false;
    }
    while (this->QueryPointId >= offsets[composite->Block + 1])
    {
      ++composite->Block;
    }
    composite->Local = static_cast<vtkIdType>(this->QueryPointId - offsets[composite->Block]);
  }
  composite->Offset = offsets[composite->Block];
  order.erase(std::find(order.begin(), order.end(), composite->Block));
  order.insert(order.begin(), composite->Block);
  this->Composite = std::move(composite);
  return true;
}

void vtkGLSMultiScaleDissimilarity::EndComposite()
{
  this->Composite.reset();
}

vtkGLSScaleFilterBase::SampleRequest vtkGLSMultiScaleDissimilarity::GetSampleRequest(const vtkGLSRun&) const
{
  SampleRequest request;
  request.Descriptors = true;
  request.MayReuseInput = this->ReuseInputScaleSpace;
  return request;
}

/// The query point's descriptors at the run's scales.
struct vtkGLSMultiScaleDissimilarity::QueryDescriptors
{
  std::vector<gls::ScaleSample> Samples;
};

int vtkGLSMultiScaleDissimilarity::ComputeOutputs(vtkGLSRun& run)
{
  const std::vector<double> prior = this->ResolvePrior(run);
  if (prior.empty())
  {
    return FAILED;
  }
  QueryDescriptors query;
  const int status = this->DescribeQuery(run, prior, query);
  return status == COMPLETED ? this->WriteDissimilarity(run, prior, query) : status;
}

std::vector<double> vtkGLSMultiScaleDissimilarity::ResolvePrior(const vtkGLSRun& run)
{
  const std::vector<double>& scales = run.Scales;
  // The prior, clipped to the sampled range so that a Gaussian is centred where there are scales.
  const double pmin = std::max(this->ToAbsoluteLength(run, this->PriorMinScale), scales.front());
  const double pmax = this->PriorMaxScale > 0.0
    ? std::min(this->ToAbsoluteLength(run, this->PriorMaxScale), scales.back())
    : scales.back();
  std::string why;
  const std::vector<double> prior =
    gls::scalePrior(scales, static_cast<gls::ScalePriorShape>(this->PriorShape), pmin, pmax, why);
  if (prior.empty())
  {
    // The range the user gave (in ScaleUnits and absolute), not its clipped form, which may come out reversed.
    vtkErrorMacro("Invalid scale prior: no sampled scale lies in [PriorMinScale, PriorMaxScale] = ["
      << this->PriorMinScale << ", " << (this->PriorMaxScale > 0.0 ? this->PriorMaxScale : scales.back())
      << "] (absolute: [" << this->ToAbsoluteLength(run, this->PriorMinScale) << ", "
      << (this->PriorMaxScale > 0.0 ? this->ToAbsoluteLength(run, this->PriorMaxScale) : scales.back())
      << "]); the sampled scales span [" << scales.front() << ", " << scales.back() << "] (absolute).");
  }
  return prior;
}

int vtkGLSMultiScaleDissimilarity::DescribeQuery(
  vtkGLSRun& run, const std::vector<double>& prior, QueryDescriptors& descriptors)
{
  const QueryState& query = static_cast<const QueryState&>(*run.State);
  const std::vector<double>& scales = run.Scales;
  // The query's descriptors: computed where it lives (with the ghosts of that piece), then sent to every rank.
  CaptureSink querySink;
  querySink.Samples.resize(scales.size());
  int queryStatus = 1; // 1 computed, 0 aborted
  const bool known = this->Composite && this->Composite->Known;
  if (known)
  {
    // A composite's other block: the query's descriptors at the same scales.
    if (this->Composite->Scales != scales)
    {
      vtkErrorMacro("The blocks of the composite input have different scales (an upstream scale space per block?): "
                    "the dissimilarity compares descriptors scale by scale; turn ReuseInputScaleSpace off.");
      return FAILED;
    }
    querySink.Samples = this->Composite->Samples;
  }
  else if (query.Index >= 0)
  {
    const std::vector<std::uint64_t> queryIds{ static_cast<std::uint64_t>(query.Index) };
    queryStatus = this->FeedSamples(run, querySink, &queryIds, 0.0, 0.02) ? 1 : 0;
  }
  if (run.Distributed.IsParallel() && !known)
  {
    static_assert(std::is_trivially_copyable<gls::ScaleSample>::value, "sent as bytes");
    vtkMultiProcessController* c = this->GetController();
    c->Broadcast(&queryStatus, 1, query.Owner);
    c->Broadcast(reinterpret_cast<char*>(querySink.Samples.data()),
      static_cast<vtkIdType>(querySink.Samples.size() * sizeof(gls::ScaleSample)), query.Owner);
  }
  if (!queryStatus)
  {
    return ABORTED;
  }
  bool anyValid = false;
  for (std::size_t k = 0; k < scales.size(); ++k)
  {
    anyValid = anyValid || (prior[k] > 0.0 && querySink.Samples[k].valid);
  }
  if (this->Composite && !known)
  {
    this->Composite->Known = true;
    this->Composite->Flat = query.GlobalId;
    this->Composite->Samples = querySink.Samples;
    this->Composite->Scales = scales;
  }
  if (!anyValid)
  {
    vtkErrorMacro("The query point " << query.GlobalId
                                     << " has no defined fit at any scale of the prior (non-finite coordinates, or "
                                        "too few neighbours): pick another point or larger scales.");
    return FAILED;
  }
  descriptors.Samples = std::move(querySink.Samples);
  return COMPLETED;
}

int vtkGLSMultiScaleDissimilarity::WriteDissimilarity(
  vtkGLSRun& run, const std::vector<double>& prior, const QueryDescriptors& query)
{
  const vtkIdType n = run.Input->GetNumberOfPoints();
  vtkNew<vtkDoubleArray> delta;
  delta->SetName(vtkGLSArrayNames::Dissimilarity);
  delta->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedCharArray> similar;
  similar->SetName(vtkGLSArrayNames::Similar);
  similar->SetNumberOfTuples(n);
  DissimilaritySink sink;
  sink.Scales = &run.Scales;
  sink.Prior = &prior;
  sink.Query = query.Samples.data();
  sink.Threshold = this->Threshold;
  sink.Delta = delta->GetPointer(0);
  sink.Similar = similar->GetPointer(0);
  if (!this->FeedSamples(run, sink, nullptr, 0.02, 1.0))
  {
    return ABORTED; // no partial arrays
  }
  vtkPointSet* output = run.Output;
  output->GetPointData()->AddArray(delta);
  output->GetPointData()->AddArray(similar);
  output->GetPointData()->SetActiveScalars(vtkGLSArrayNames::Dissimilarity);
  vtkNew<vtkIdTypeArray> queryArray;
  queryArray->SetName(vtkGLSArrayNames::QueryPointId);
  queryArray->InsertNextValue(static_cast<vtkIdType>(static_cast<const QueryState&>(*run.State).GlobalId));
  output->GetFieldData()->AddArray(queryArray);
  return COMPLETED;
}

double vtkGLSMultiScaleDissimilarity::QueryDistanceScale() const
{
  const double largest =
    std::max({ std::abs(this->QueryPoint[0]), std::abs(this->QueryPoint[1]), std::abs(this->QueryPoint[2]) });
  // A power of two (exact: the order of distances is kept) that brings coordinates beyond 1e150 down to about 1.
  return largest > 1e150 && std::isfinite(largest) ? std::ldexp(1.0, std::ilogb(largest)) : 1.0;
}

double vtkGLSMultiScaleDissimilarity::QueryDistance2(const double p[3]) const
{
  const double s = 1.0 / this->QueryDistanceScale();
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const double d = p[a] * s - this->QueryPoint[a] * s;
    d2 += d * d;
  }
  return std::isfinite(d2) ? d2 : std::numeric_limits<double>::infinity();
}

bool vtkGLSMultiScaleDissimilarity::CheckQueryPointIsNear(const vtkGLSRun& run, double best2)
{
  const double nearest = std::sqrt(best2) * this->QueryDistanceScale();
  if (nearest <= run.Diagonal || run.Diagonal == 0.0)
  {
    return true;
  }
  const double* q = this->QueryPoint;
  vtkErrorMacro("QueryPoint (" << q[0] << ", " << q[1] << ", " << q[2] << ") is " << nearest
                               << " from the nearest input point, farther than the input's bounding-box diagonal ("
                               << run.Diagonal
                               << "): it is not on this cloud (coordinates of another frame?). Pick a point of the "
                                  "cloud, or QueryPointId.");
  return false;
}

bool vtkGLSMultiScaleDissimilarity::LocateDistributedQuery(const vtkGLSRun& run, vtkIdType wanted,
  double localBest2, vtkIdType& query, long long& globalId, int& owner)
{
  vtkPointSet* input = run.Input;
  const vtkGLSDistributedCloud& dist = run.Distributed;
  const std::vector<long long> ids = dist.GlobalIds(input);
  const double none = std::numeric_limits<double>::infinity();
  if (this->UseQueryPointCoordinates)
  {
    // The nearest point over all pieces; among equally near ones the smallest global id (the serial choice, the
    // first such point, when the global ids follow the serial order).
    const double best2 = dist.Min(query >= 0 ? localBest2 : none);
    if (!(best2 < none))
    {
      vtkErrorMacro("No input point with finite coordinates to snap the query point to.");
      return false;
    }
    if (!this->CheckQueryPointIsNear(run, best2)) // every rank: the same global values
    {
      return false;
    }
    double mine = none;
    for (std::size_t i = 0; i < ids.size(); ++i)
    {
      double p[3];
      input->GetPoint(static_cast<vtkIdType>(i), p);
      if (this->QueryDistance2(p) == best2)
      {
        mine = std::min(mine, static_cast<double>(ids[i]));
      }
    }
    globalId = static_cast<long long>(dist.Min(mine));
  }
  else
  {
    globalId = wanted;
  }
  query = -1;
  for (std::size_t i = 0; i < ids.size() && query < 0; ++i)
  {
    if (ids[i] == globalId)
    {
      query = static_cast<vtkIdType>(i);
    }
  }
  owner = static_cast<int>(dist.Min(query >= 0 ? dist.GetRank() : dist.GetSize()));
  if (owner >= dist.GetSize())
  {
    vtkErrorMacro("QueryPointId " << globalId << " is out of range: no piece has a point with that global id (the "
                                  << static_cast<long long>(dist.Sum(static_cast<double>(input->GetNumberOfPoints())))
                                  << " points are numbered by their GlobalIds, else in rank order).");
    return false;
  }
  if (dist.GetRank() != owner)
  {
    query = -1; // a duplicated global id: the lowest rank holding it owns the query
  }
  return true;
}

void vtkGLSMultiScaleDissimilarity::DescribeSettings(std::vector<SettingRange>& settings)
{
  this->Superclass::DescribeSettings(settings);
  settings.push_back({ "PriorShape", static_cast<double>(this->PriorShape), static_cast<double>(BOX), static_cast<double>(LOG_GAUSSIAN) });
  settings.push_back({ "Threshold", static_cast<double>(this->Threshold), static_cast<double>(0.0), static_cast<double>(VTK_DOUBLE_MAX) });
}

void vtkGLSMultiScaleDissimilarity::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ReuseInputScaleSpace: " << this->ReuseInputScaleSpace << "\n";
  os << indent << "QueryPointId: " << this->QueryPointId << "\n";
  os << indent << "QueryPoint: " << this->QueryPoint[0] << ", " << this->QueryPoint[1] << ", " << this->QueryPoint[2]
     << "\n";
  os << indent << "UseQueryPointCoordinates: " << this->UseQueryPointCoordinates << "\n";
  os << indent << "PriorMinScale: " << this->PriorMinScale << "\n";
  os << indent << "PriorMaxScale: " << this->PriorMaxScale << "\n";
  os << indent << "PriorShape: " << (this->PriorShape == BOX ? "Box" : "LogGaussian") << "\n";
  os << indent << "Threshold: " << this->Threshold << "\n";
}
