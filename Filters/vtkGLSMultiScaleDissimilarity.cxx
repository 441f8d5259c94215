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
  vtkPointSet* input = run.Input;
  const vtkIdType n = input->GetNumberOfPoints();
  const vtkGLSDistributedCloud& dist = run.Distributed;
  auto state = std::make_unique<QueryState>();
  if (!this->UseQueryPointCoordinates && this->QueryPointId < 0)
  {
    vtkErrorMacro("QueryPointId must be a point id, >= 0 (it is " << this->QueryPointId << ").");
    return false;
  }
  // The query point (in a distributed run, this piece's index of it, -1 on the other ranks).
  vtkIdType query = this->QueryPointId;
  double best = VTK_DOUBLE_MAX;
  if (this->UseQueryPointCoordinates)
  {
    query = -1;
    for (vtkIdType i = 0; i < n; ++i)
    {
      double p[3];
      input->GetPoint(i, p);
      const double d2 = vtkMath::Distance2BetweenPoints(p, this->QueryPoint);
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
  }
  long long queryGlobalId = query;
  if (dist.IsParallel() && !this->LocateDistributedQuery(run, best, query, queryGlobalId, state->Owner))
  {
    return false;
  }
  if (!dist.IsParallel() && query >= n)
  {
    vtkErrorMacro("QueryPointId " << query << " is out of range: the input has " << n << " points.");
    return false;
  }
  state->Index = query;
  state->GlobalId = queryGlobalId;
  run.State = std::move(state);
  return true;
}

vtkGLSScaleFilterBase::SampleRequest vtkGLSMultiScaleDissimilarity::GetSampleRequest(const vtkGLSRun&) const
{
  SampleRequest request;
  request.Descriptors = true;
  request.MayReuseInput = this->ReuseInputScaleSpace;
  return request;
}

int vtkGLSMultiScaleDissimilarity::ComputeOutputs(vtkGLSRun& run)
{
  const QueryState& query = static_cast<const QueryState&>(*run.State);
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
    vtkErrorMacro("Invalid scale prior: " << why << " (sampled scales span [" << scales.front() << ", "
                                          << scales.back() << "]).");
    return FAILED;
  }

  // The query's descriptors: computed where it lives (with the ghosts of that piece), then sent to every rank.
  CaptureSink querySink;
  querySink.Samples.resize(scales.size());
  int queryStatus = 1; // 1 computed, 0 aborted
  if (query.Index >= 0)
  {
    const std::vector<std::uint64_t> queryIds{ static_cast<std::uint64_t>(query.Index) };
    queryStatus = this->FeedSamples(run, querySink, &queryIds, 0.0, 0.02) ? 1 : 0;
  }
  if (run.Distributed.IsParallel())
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
  if (!anyValid)
  {
    vtkErrorMacro("The query point " << query.GlobalId
                                     << " has no defined fit at any scale of the prior (non-finite coordinates, or "
                                        "too few neighbours): pick another point or larger scales.");
    return FAILED;
  }

  const vtkIdType n = run.Input->GetNumberOfPoints();
  vtkNew<vtkDoubleArray> delta;
  delta->SetName(vtkGLSArrayNames::Dissimilarity);
  delta->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedCharArray> similar;
  similar->SetName(vtkGLSArrayNames::Similar);
  similar->SetNumberOfTuples(n);
  DissimilaritySink sink;
  sink.Scales = &scales;
  sink.Prior = &prior;
  sink.Query = querySink.Samples.data();
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
  queryArray->InsertNextValue(static_cast<vtkIdType>(query.GlobalId));
  output->GetFieldData()->AddArray(queryArray);
  return COMPLETED;
}

bool vtkGLSMultiScaleDissimilarity::LocateDistributedQuery(
  const vtkGLSRun& run, double localBest2, vtkIdType& query, long long& globalId, int& owner)
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
    double mine = none;
    for (std::size_t i = 0; i < ids.size(); ++i)
    {
      double p[3];
      input->GetPoint(static_cast<vtkIdType>(i), p);
      if (vtkMath::Distance2BetweenPoints(p, this->QueryPoint) == best2)
      {
        mine = std::min(mine, static_cast<double>(ids[i]));
      }
    }
    globalId = static_cast<long long>(dist.Min(mine));
  }
  else
  {
    globalId = this->QueryPointId;
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
