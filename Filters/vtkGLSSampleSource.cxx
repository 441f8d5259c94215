#include "vtkGLSSampleSource.h"

#include "vtkGLSDescriptors.h"
#include "vtkGLSRun.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include "gls/Numeric.h"

#include <cmath>

std::unique_ptr<vtkGLSSampleSource> vtkGLSSampleSource::Fit(
  const vtkGLSCloud& cloud, gls::ScaleSpaceSettings settings)
{
  std::unique_ptr<vtkGLSSampleSource> source(new vtkGLSSampleSource);
  source->PointCount = cloud.Owned;
  source->ScaleCount = settings.scales.size();
  if (cloud.Owned == 0)
  {
    return source; // an empty piece of a distributed input: nothing to fit
  }
  source->Engine = std::make_unique<gls::ScaleSpaceEngine>(
    cloud.Points.data(), cloud.Normals.data(), cloud.Size(), std::move(settings));
  if (cloud.Ghosts() > 0)
  {
    for (std::uint64_t id : source->Engine->evaluationOrder())
    {
      if (id < cloud.Owned)
      {
        source->OwnedOrder.push_back(id);
      }
    }
  }
  return source;
}

std::unique_ptr<vtkGLSSampleSource> vtkGLSSampleSource::Stored(
  vtkPolyData* input, std::size_t scaleCount, bool descriptors, bool derivatives)
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
    vtkDataArray* a = input->GetPointData()->GetArray(d.Name);
    if (!a || a->GetNumberOfComponents() != d.Components * static_cast<int>(scaleCount) ||
      a->GetNumberOfTuples() != input->GetNumberOfPoints())
    {
      return nullptr;
    }
    source->StoredArrays.emplace_back(id, a);
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
  const gls::ParallelOptions& parallel, gls::Backend backend, gls::RunReport& report) const
{
  report = gls::RunReport();
  if (this->Engine)
  {
    const std::vector<std::uint64_t>* order = ids || this->OwnedOrder.empty() ? ids : &this->OwnedOrder;
    return this->Engine->run(sink, order, gls::EvaluationMethod::OnePass, &parallel, backend, &report);
  }
  report.used = gls::Backend::CPU;
  const std::size_t n = ids ? ids->size() : this->PointCount;
  const std::size_t S = this->ScaleCount;
  const double nan = gls::quietNaN<double>();
  std::vector<std::vector<gls::ScaleSample>> buffers(static_cast<std::size_t>(gls::resolveThreadCount(parallel.threads)));
  return gls::parallelFor(n, parallel, [&](std::size_t begin, std::size_t end, int thread) {
    std::vector<gls::ScaleSample>& samples = buffers[static_cast<std::size_t>(thread)];
    samples.resize(S);
    for (std::size_t i = begin; i < end; ++i)
    {
      const std::uint64_t point = ids ? (*ids)[i] : i;
      const vtkIdType tuple = static_cast<vtkIdType>(point);
      for (std::size_t k = 0; k < S; ++k)
      {
        gls::ScaleSample& s = samples[k];
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
      }
      sink.consume(point, samples.data(), thread);
    }
  });
}

double vtkGLSSampleSource::EngineBytes(std::size_t n, std::size_t S, int threads)
{
  const double perPoint = 6 * 8 + 2 * 3 * 8 + 3 * 8 + 8; // input copies, grid copies, positions, order
  const double perThread = static_cast<double>(S) * (sizeof(gls::Moments) + sizeof(gls::ScaleSample) + 8);
  return static_cast<double>(n) * perPoint + static_cast<double>(threads) * perThread;
}
