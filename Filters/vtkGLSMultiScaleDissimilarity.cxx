#include "vtkGLSMultiScaleDissimilarity.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSDistributedCloud.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
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

} // namespace

vtkGLSMultiScaleDissimilarity::vtkGLSMultiScaleDissimilarity()
  : QueryPointId(0)
  , QueryPoint{ 0.0, 0.0, 0.0 }
  , UseQueryPointCoordinates(false)
  , PriorMinScale(0.0)
  , PriorMaxScale(0.0)
  , PriorShape(BOX)
  , Threshold(0.01)
{
}

vtkGLSMultiScaleDissimilarity::~vtkGLSMultiScaleDissimilarity() = default;

int vtkGLSMultiScaleDissimilarity::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!this->PrepareOutput(input, output))
  {
    return 0;
  }
  const vtkIdType n = input->GetNumberOfPoints();
  const vtkGLSDistributedCloud& dist = this->Distributed();

  // The query point (in a distributed run, `query` is this piece's index of it, -1 on the other ranks).
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
      return 0;
    }
  }
  long long queryGlobalId = query;
  if (dist.IsParallel() && !this->LocateDistributedQuery(input, best, query, queryGlobalId))
  {
    return 0;
  }
  if (!dist.IsParallel() && query >= n)
  {
    vtkErrorMacro("QueryPointId " << query << " is out of range: the input has " << n << " points.");
    return 0;
  }

  std::vector<double> scales;
  if (!this->PrepareScaleSamples(input, true, false, scales))
  {
    return 0;
  }
  // The prior, clipped to the sampled range so that a Gaussian is centred where there are scales.
  const double pmin = std::max(this->ToAbsoluteLength(input, this->PriorMinScale), scales.front());
  const double pmax = this->PriorMaxScale > 0.0
    ? std::min(this->ToAbsoluteLength(input, this->PriorMaxScale), scales.back())
    : scales.back();
  std::string why;
  const std::vector<double> prior =
    gls::scalePrior(scales, static_cast<gls::ScalePriorShape>(this->PriorShape), pmin, pmax, why);
  if (prior.empty())
  {
    vtkErrorMacro("Invalid scale prior: " << why << " (sampled scales span [" << scales.front() << ", "
                                          << scales.back() << "]).");
    return 0;
  }

  // The query's descriptors: computed where it lives (with the ghosts of that piece), then sent to every rank.
  CaptureSink querySink;
  querySink.Samples.resize(scales.size());
  int queryStatus = 1; // 1 computed, 0 aborted
  if (query >= 0)
  {
    const std::vector<std::uint64_t> queryIds{ static_cast<std::uint64_t>(query) };
    queryStatus = this->RunScaleSamples(querySink, &queryIds, 0.0, 0.02) ? 1 : 0;
  }
  if (dist.IsParallel())
  {
    static_assert(std::is_trivially_copyable<gls::ScaleSample>::value, "sent as bytes");
    vtkMultiProcessController* c = this->GetController();
    c->Broadcast(&queryStatus, 1, this->QueryOwner);
    c->Broadcast(reinterpret_cast<char*>(querySink.Samples.data()),
      static_cast<vtkIdType>(querySink.Samples.size() * sizeof(gls::ScaleSample)), this->QueryOwner);
  }
  if (!queryStatus)
  {
    return 1; // aborted
  }
  bool anyValid = false;
  for (std::size_t k = 0; k < scales.size(); ++k)
  {
    anyValid = anyValid || (prior[k] > 0.0 && querySink.Samples[k].valid);
  }
  if (!anyValid)
  {
    vtkErrorMacro("The query point " << queryGlobalId
                                     << " has no defined fit at any scale of the prior (non-finite coordinates, or "
                                        "too few neighbours): pick another point or larger scales.");
    return 0;
  }

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
  if (!this->RunScaleSamples(sink, nullptr, 0.02, 1.0))
  {
    return 1; // aborted: no partial arrays
  }
  output->GetPointData()->AddArray(delta);
  output->GetPointData()->AddArray(similar);
  output->GetPointData()->SetActiveScalars(vtkGLSArrayNames::Dissimilarity);
  vtkNew<vtkIdTypeArray> queryArray;
  queryArray->SetName(vtkGLSArrayNames::QueryPointId);
  queryArray->InsertNextValue(static_cast<vtkIdType>(queryGlobalId));
  output->GetFieldData()->AddArray(queryArray);
  StoreScales(output->GetFieldData(), scales);
  this->StoreBackend(output->GetFieldData());
  return 1;
}

bool vtkGLSMultiScaleDissimilarity::LocateDistributedQuery(
  vtkPolyData* input, double localBest2, vtkIdType& query, long long& globalId)
{
  const vtkGLSDistributedCloud& dist = this->Distributed();
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
  this->QueryOwner = static_cast<int>(dist.Min(query >= 0 ? dist.GetRank() : dist.GetSize()));
  if (this->QueryOwner >= dist.GetSize())
  {
    vtkErrorMacro("QueryPointId " << globalId << " is out of range: no piece has a point with that global id (the "
                                  << static_cast<long long>(dist.Sum(static_cast<double>(input->GetNumberOfPoints())))
                                  << " points are numbered by their GlobalIds, else in rank order).");
    return false;
  }
  if (dist.GetRank() != this->QueryOwner)
  {
    query = -1; // a duplicated global id: the lowest rank holding it owns the query
  }
  return true;
}

void vtkGLSMultiScaleDissimilarity::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "QueryPointId: " << this->QueryPointId << "\n";
  os << indent << "QueryPoint: " << this->QueryPoint[0] << ", " << this->QueryPoint[1] << ", " << this->QueryPoint[2]
     << "\n";
  os << indent << "UseQueryPointCoordinates: " << this->UseQueryPointCoordinates << "\n";
  os << indent << "PriorMinScale: " << this->PriorMinScale << "\n";
  os << indent << "PriorMaxScale: " << this->PriorMaxScale << "\n";
  os << indent << "PriorShape: " << (this->PriorShape == BOX ? "Box" : "LogGaussian") << "\n";
  os << indent << "Threshold: " << this->Threshold << "\n";
}
