#include "vtkGLSSampleSource.h"

#include "vtkGLSDescriptors.h"
#include "vtkGLSRun.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkDataSet.h"

#include "gls/Numeric.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace
{

/// Forwards the samples of a distinct position to the input points it stands for: all of this piece's copies, or
/// the requested ones (`requested`: pairs of distinct position and input id, sorted).
class CopiesSink : public gls::ScaleSampleSink
{
public:
  CopiesSink(gls::ScaleSampleSink& inner, const vtkGLSCloud& cloud,
    const std::vector<std::pair<std::uint64_t, std::uint64_t>>* requested)
    : Inner(inner)
    , Cloud(cloud)
    , Requested(requested)
  {
  }

  void consume(std::uint64_t position, const gls::ScaleSample* samples, int thread) override
  {
    this->forEachCopy(position, [&](std::uint64_t id) { this->Inner.consume(id, samples, thread); });
  }

  void consumeCurvatures(std::uint64_t position, const gls::PrincipalCurvatures* c, int thread) override
  {
    this->forEachCopy(position, [&](std::uint64_t id) { this->Inner.consumeCurvatures(id, c, thread); });
  }

private:
  /// Calls pass(id) for each input point the distinct position stands for.
  template <typename Pass>
  void forEachCopy(std::uint64_t position, const Pass& pass) const
  {
    if (this->Requested)
    {
      auto it = std::lower_bound(this->Requested->begin(), this->Requested->end(),
        std::make_pair(position, std::uint64_t(0)));
      for (; it != this->Requested->end() && it->first == position; ++it)
      {
        pass(it->second);
      }
      return;
    }
    const gls::CoincidentPoints& c = this->Cloud.Copies;
    for (std::uint64_t k = c.copyStart[position]; k < c.copyStart[position + 1]; ++k)
    {
      if (c.copies[k] < this->Cloud.InputOwned)
      {
        pass(c.copies[k]);
      }
    }
  }

  gls::ScaleSampleSink& Inner;
  const vtkGLSCloud& Cloud;
  const std::vector<std::pair<std::uint64_t, std::uint64_t>>* Requested;
};

/// The point array `name` of a stored scale space: `components` values per scale for `scaleCount` scales at every
/// point; null when it is missing or has another shape.
vtkDataArray* StoredArray(vtkDataSet* input, const char* name, int components, std::size_t scaleCount)
{
  vtkDataArray* a = input->GetPointData()->GetArray(name);
  const bool shaped = a && a->GetNumberOfComponents() == components * static_cast<int>(scaleCount) &&
    a->GetNumberOfTuples() == input->GetNumberOfPoints();
  return shaped ? a : nullptr;
}

}

std::unique_ptr<vtkGLSSampleSource> vtkGLSSampleSource::OfCloud(const vtkGLSCloud& cloud, std::size_t scales)
{
  std::unique_ptr<vtkGLSSampleSource> source(new vtkGLSSampleSource);
  source->PointCount = cloud.Owned;
  source->ScaleCount = scales;
  source->Cloud = &cloud;
  return source;
}

std::unique_ptr<vtkGLSSampleSource> vtkGLSSampleSource::Fit(
  const vtkGLSCloud& cloud, gls::ScaleSpaceSettings settings, std::size_t tiles)
{
  std::unique_ptr<vtkGLSSampleSource> source = OfCloud(cloud, settings.scales.size());
  if (cloud.Owned == 0)
  {
    return source; // an empty piece of a distributed input: nothing to fit
  }
  source->Engine = std::make_unique<gls::TiledScaleSpace>(
    cloud.Points.data(), cloud.Normals.data(), cloud.Size(), cloud.Owned, std::move(settings), tiles);
  return source;
}

std::unique_ptr<vtkGLSSampleSource> vtkGLSSampleSource::FitWholeReleasing(
  vtkGLSCloud& cloud, gls::ScaleSpaceSettings settings)
{
  std::unique_ptr<vtkGLSSampleSource> source = OfCloud(cloud, settings.scales.size());
  if (cloud.Owned == 0)
  {
    return source; // an empty piece of a distributed input: nothing to fit
  }
  source->Engine = std::make_unique<gls::TiledScaleSpace>(cloud.Points.data(), cloud.Normals.data(), cloud.Size(),
    cloud.Owned, std::move(settings), 1, [&cloud] { cloud.ReleaseCoordinates(); });
  return source;
}

std::unique_ptr<vtkGLSSampleSource> vtkGLSSampleSource::FitAround(
  const vtkGLSCloud& cloud, gls::ScaleSpaceSettings settings, const std::vector<std::uint64_t>& only)
{
  std::unique_ptr<vtkGLSSampleSource> source = OfCloud(cloud, settings.scales.size());
  if (cloud.Owned == 0)
  {
    return source; // an empty piece of a distributed input: nothing to fit
  }
  std::vector<std::uint64_t> positions; // the distinct positions of the points, as Feed evaluates them
  for (std::uint64_t id : only)
  {
    positions.push_back(cloud.IsMerged() ? cloud.Copies.representative[id] : id);
  }
  source->Engine = std::make_unique<gls::TiledScaleSpace>(
    cloud.Points.data(), cloud.Normals.data(), cloud.Size(), cloud.Owned, std::move(settings), positions);
  return source;
}

std::unique_ptr<vtkGLSSampleSource> vtkGLSSampleSource::Stored(
  vtkDataSet* input, std::size_t scaleCount, bool descriptors, bool derivatives, bool curvatures)
{
  std::unique_ptr<vtkGLSSampleSource> source(new vtkGLSSampleSource);
  source->PointCount = static_cast<std::size_t>(input->GetNumberOfPoints());
  source->ScaleCount = scaleCount;
  for (int id = 0; id < vtkGLSDescriptors::NUMBER_OF_DESCRIPTORS; ++id)
  {
    const vtkGLSDescriptors::Descriptor& d = vtkGLSDescriptors::Get(static_cast<vtkGLSDescriptors::Id>(id));
    const bool wanted = (descriptors && d.ReadBack == vtkGLSDescriptors::DESCRIPTOR) ||
      (derivatives && d.ReadBack == vtkGLSDescriptors::DERIVATIVE);
    if (!wanted)
    {
      continue;
    }
    vtkDataArray* a = StoredArray(input, d.Name, d.Components, scaleCount);
    if (!a)
    {
      return nullptr;
    }
    source->StoredArrays.emplace_back(id, a);
  }
  for (int id = 0; curvatures && id < vtkGLSDescriptors::NUMBER_OF_CURVATURE_ARRAYS; ++id)
  {
    const vtkGLSDescriptors::CurvatureArray& c =
      vtkGLSDescriptors::GetCurvature(static_cast<vtkGLSDescriptors::CurvatureId>(id));
    if (!c.Read)
    {
      continue;
    }
    vtkDataArray* a = StoredArray(input, c.Name, c.Components, scaleCount);
    if (!a)
    {
      return nullptr;
    }
    source->StoredCurvatures.emplace_back(id, a);
  }
  if (scaleCount == 0)
  {
    return nullptr;
  }
  return source;
}

std::unique_ptr<vtkGLSSampleSource> vtkGLSSampleSource::Empty()
{
  return std::unique_ptr<vtkGLSSampleSource>(new vtkGLSSampleSource);
}

bool vtkGLSSampleSource::Feed(gls::ScaleSampleSink& sink, const std::vector<std::uint64_t>* ids,
  const gls::ParallelOptions& parallel, gls::RunReport& report) const
{
  report = gls::RunReport();
  if (this->Engine && this->Cloud->IsMerged())
  {
    return this->FeedDistinctPositions(sink, ids, parallel, report);
  }
  if (this->Engine)
  {
    return this->Engine->run(sink, ids, parallel, report);
  }
  report.used = gls::Backend::CPU;
  return this->FeedStored(sink, ids, parallel);
}

bool vtkGLSSampleSource::FeedDistinctPositions(gls::ScaleSampleSink& sink, const std::vector<std::uint64_t>* ids,
  const gls::ParallelOptions& parallel, gls::RunReport& report) const
{
  std::vector<std::pair<std::uint64_t, std::uint64_t>> requested;
  std::vector<std::uint64_t> positions;
  if (ids)
  {
    for (std::uint64_t id : *ids)
    {
      requested.emplace_back(this->Cloud->Copies.representative[id], id);
    }
    std::sort(requested.begin(), requested.end());
    for (const auto& r : requested)
    {
      if (positions.empty() || positions.back() != r.first)
      {
        positions.push_back(r.first);
      }
    }
  }
  CopiesSink copies(sink, *this->Cloud, ids ? &requested : nullptr);
  return this->Engine->run(copies, ids ? &positions : nullptr, parallel, report);
}

bool vtkGLSSampleSource::FeedStored(
  gls::ScaleSampleSink& sink, const std::vector<std::uint64_t>* ids, const gls::ParallelOptions& parallel) const
{
  const std::size_t n = ids ? ids->size() : this->PointCount;
  const std::size_t S = this->ScaleCount;
  const std::size_t threads = static_cast<std::size_t>(gls::resolveThreadCount(parallel.threads));
  std::vector<std::vector<gls::ScaleSample>> buffers(threads);
  std::vector<std::vector<gls::PrincipalCurvatures>> curvatureBuffers(threads);
  return gls::parallelFor(n, parallel, [&](std::size_t begin, std::size_t end, int thread) {
    std::vector<gls::ScaleSample>& samples = buffers[static_cast<std::size_t>(thread)];
    std::vector<gls::PrincipalCurvatures>& curvatures = curvatureBuffers[static_cast<std::size_t>(thread)];
    samples.resize(S);
    curvatures.resize(this->StoredCurvatures.empty() ? 0 : S);
    for (std::size_t i = begin; i < end; ++i)
    {
      const std::uint64_t point = ids ? (*ids)[i] : i;
      for (std::size_t k = 0; k < S; ++k)
      {
        samples[k] = this->StoredSample(static_cast<vtkIdType>(point), k);
      }
      if (!this->StoredCurvatures.empty())
      {
        for (std::size_t k = 0; k < S; ++k)
        {
          curvatures[k] = this->StoredCurvature(static_cast<vtkIdType>(point), k);
        }
        sink.consumeCurvatures(point, curvatures.data(), thread);
      }
      sink.consume(point, samples.data(), thread);
    }
  });
}

gls::ScaleSample vtkGLSSampleSource::StoredSample(vtkIdType tuple, std::size_t k) const
{
  const double nan = gls::quietNaN<double>();
  gls::ScaleSample s;
  s.tau = s.kappa = s.phi = s.dtau = s.dkappa = s.neighbors = nan;
  s.eta = s.deta = gls::Vec3{ nan, nan, nan };
  bool valid = true;
  for (const auto& stored : this->StoredArrays)
  {
    const vtkGLSDescriptors::Descriptor& d = vtkGLSDescriptors::Get(static_cast<vtkGLSDescriptors::Id>(stored.first));
    for (int c = 0; c < d.Components; ++c)
    {
      const double v = stored.second->GetComponent(tuple, static_cast<int>(k) * d.Components + c);
      vtkGLSDescriptors::SetValue(d, s, c, v);
      valid = valid && std::isfinite(v);
    }
  }
  s.valid = valid;
  return s;
}

gls::PrincipalCurvatures vtkGLSSampleSource::StoredCurvature(vtkIdType tuple, std::size_t k) const
{
  gls::PrincipalCurvatures c = gls::undefinedCurvatures();
  for (const auto& stored : this->StoredCurvatures)
  {
    const vtkGLSDescriptors::CurvatureArray& a =
      vtkGLSDescriptors::GetCurvature(static_cast<vtkGLSDescriptors::CurvatureId>(stored.first));
    for (int j = 0; j < a.Components; ++j)
    {
      a.Read(c, j, stored.second->GetComponent(tuple, static_cast<int>(k) * a.Components + j));
    }
  }
  return c;
}

gls::EngineFootprint vtkGLSSampleSource::EngineBytes(
  const vtkGLSCloud& cloud, const gls::ScaleSpaceSettings& settings)
{
  return gls::ScaleSpaceEngine::footprint(cloud.Points.data(), cloud.Normals.data(), cloud.Size(), settings);
}

double vtkGLSSampleSource::EngineShareBytes(
  double wholeEngineBytes, std::size_t wholePoints, std::size_t points, std::size_t S, int threads)
{
  // A tile's engine: the whole cloud's per point (a tile is laid on the whole cloud's lattice, of its density).
  const double share = wholePoints > 0 ? wholeEngineBytes * static_cast<double>(points) / wholePoints : 0.0;
  const double perThread = static_cast<double>(S) * (sizeof(gls::Moments) + sizeof(gls::ScaleSample) + 8);
  return share + static_cast<double>(threads) * perThread;
}
