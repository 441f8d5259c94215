#include "vtkGLSScaleSpaceImage.h"

#include "vtkGLSCurve.h"
#include "vtkGLSDescriptors.h"
#include "vtkGLSRun.h"

#include "vtkCellArray.h"
#include "vtkContourFilter.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStripper.h"

#include "gls/CurveGeometry.h"
#include "gls/Descriptors.h"
#include "gls/Planarity.h"
#include "gls/ScaleSpaceEngine.h"

#include <algorithm>
#include <cmath>
#include <limits>

vtkStandardNewMacro(vtkGLSScaleSpaceImage);

namespace
{

constexpr const char* ScaledKappaName = "GLSScaledKappa";
const char* KappaName()
{
  return vtkGLSDescriptors::Get(vtkGLSDescriptors::KAPPA).Name;
}
constexpr const char* NuName = "GLSNu";

/// Keeps kappa and nu of every curve point at every scale (point-major).
class CurveSink : public gls::ScaleSampleSink
{
public:
  CurveSink(std::size_t points, const std::vector<double>& scales, const gls::VariationWeights& weights)
    : Scales(scales)
    , Weights(weights)
    , Kappa(points * scales.size())
    , Nu(points * scales.size())
  {
  }
  void consume(std::uint64_t id, const gls::ScaleSample* s, int) override
  {
    const std::size_t S = this->Scales.size();
    for (std::size_t k = 0; k < S; ++k)
    {
      this->Kappa[id * S + k] = s[k].kappa;
      this->Nu[id * S + k] = gls::geometricVariation(s[k], this->Scales[k], this->Weights);
    }
  }
  const std::vector<double>& Scales;
  gls::VariationWeights Weights;
  std::vector<double> Kappa;
  std::vector<double> Nu;
};

vtkSmartPointer<vtkDoubleArray> NewArray(const char* name, vtkIdType n)
{
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfTuples(n);
  return a;
}

/// The 0-isolines of the image's GLSKappa as polylines, without the segments that touch NaN values. The contouring
/// of a 2D image (vtkSynchronizedTemplates2D behind vtkContourFilter) writes single-precision points.
void ZeroCrossings(vtkImageData* image, vtkPolyData* output)
{
  vtkNew<vtkImageData> copy;
  copy->ShallowCopy(image);
  vtkNew<vtkContourFilter> contour;
  contour->SetInputData(copy);
  contour->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, KappaName());
  contour->SetValue(0, 0.0);
  contour->ComputeScalarsOff();
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->Update();
  vtkPolyData* raw = contour->GetOutput();

  // NaN kappa is classified as negative by the contouring and interpolates to NaN coordinates: drop those segments.
  vtkNew<vtkPolyData> finite;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  std::vector<vtkIdType> map(static_cast<std::size_t>(raw->GetNumberOfPoints()), -1);
  vtkCellArray* rawLines = raw->GetLines();
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  for (rawLines->InitTraversal(); rawLines->GetNextCell(npts, pts);)
  {
    bool ok = true;
    for (vtkIdType j = 0; j < npts && ok; ++j)
    {
      double p[3];
      raw->GetPoint(pts[j], p);
      ok = std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
    }
    if (!ok)
    {
      continue;
    }
    std::vector<vtkIdType> cell;
    for (vtkIdType j = 0; j < npts; ++j)
    {
      vtkIdType& m = map[static_cast<std::size_t>(pts[j])];
      if (m < 0)
      {
        m = points->InsertNextPoint(raw->GetPoint(pts[j]));
      }
      cell.push_back(m);
    }
    lines->InsertNextCell(static_cast<vtkIdType>(cell.size()), cell.data());
  }
  finite->SetPoints(points);
  finite->SetLines(lines);

  vtkNew<vtkStripper> stripper;
  stripper->SetInputData(finite);
  stripper->JoinContiguousSegmentsOn();
  stripper->Update();
  output->ShallowCopy(stripper->GetOutput());
}

/// The curve of a run, its arclengths and the number of image columns.
struct CurveState : vtkGLSRunState
{
  vtkGLSCurve::Curve Curve;
  std::vector<double> Arclength;
  int Columns = 0;
};

} // namespace

vtkGLSScaleSpaceImage::vtkGLSScaleSpaceImage()
  : Closed(CLOSED_AUTO)
  , NumberOfArclengthSamples(1000)
{
  this->NumberOfScales = 200;
  this->ScaleSampling = LINEAR; // always linear: the image rows are equally spaced in t
  this->SetNumberOfOutputPorts(2);
}

vtkGLSScaleSpaceImage::~vtkGLSScaleSpaceImage() = default;

vtkImageData* vtkGLSScaleSpaceImage::GetImageOutput()
{
  return vtkImageData::SafeDownCast(this->GetOutputDataObject(0));
}

vtkPolyData* vtkGLSScaleSpaceImage::GetCrossingsOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(1));
}

int vtkGLSScaleSpaceImage::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkGLSScaleSpaceImage::RequestDataObject(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  return this->MakeDeclaredOutputs(outputVector);
}

int vtkGLSScaleSpaceImage::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkImageData" : "vtkPolyData");
  return 1;
}

int vtkGLSScaleSpaceImage::ExecuteInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // The image's extent depends on the curve (one column per curve point by default). It is announced here when the
  // input data is already at hand (ParaView's renderers ask for the whole extent before RequestData), and again by
  // RequestData.
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int rows = this->ExplicitScales.empty() ? this->NumberOfScales
                                                : static_cast<int>(this->ExplicitScales.size());
  int columns = this->NumberOfArclengthSamples > 0 ? std::max(this->NumberOfArclengthSamples, 2) : 0;
  if (columns == 0 && input && input->GetNumberOfPoints() > 0)
  {
    vtkGLSCurve::Curve curve;
    if (vtkGLSCurve::Extract(input, this->Closed, curve).empty())
    {
      columns = static_cast<int>(curve.Ids.size()) + (curve.Closed ? 1 : 0);
    }
  }
  if (columns > 0 && rows > 0)
  {
    const int extent[6] = { 0, columns - 1, 0, rows - 1, 0, 0 };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  }
  return 1;
}

void vtkGLSScaleSpaceImage::PrepareOutputs(vtkGLSRun&) {}

bool vtkGLSScaleSpaceImage::DistributeRun(vtkGLSRun& run)
{
  const vtkGLSDistributedCloud& dist = run.Distributed;
  if (!dist.IsParallel())
  {
    return true;
  }
  // A curve is not cut into pieces: the one rank that holds it (a source that ignores piece requests gives it all
  // to rank 0) computes the image as a serial run; the other ranks give empty outputs.
  const vtkIdType local = run.Input ? run.Input->GetNumberOfPoints() : 0;
  const double holders = dist.Sum(local > 0 ? 1.0 : 0.0);
  if (holders != 1.0)
  {
    vtkErrorMacro("In a distributed run the curve must be on one process; "
      << holders << " of the " << dist.GetSize() << " processes hold points.");
    return false;
  }
  run.Idle = local == 0;
  run.Distributed = vtkGLSDistributedCloud(nullptr);
  return true;
}

bool vtkGLSScaleSpaceImage::CheckParameters(vtkGLSRun& run)
{
  if (!this->Superclass::CheckParameters(run))
  {
    return false;
  }
  auto state = std::make_unique<CurveState>();
  vtkPolyData* input = vtkPolyData::SafeDownCast(run.Input);
  const bool hasLines = input->GetLines() && input->GetLines()->GetNumberOfCells() > 0;
  const bool hasSurface = (input->GetPolys() && input->GetPolys()->GetNumberOfCells() > 0) ||
    (input->GetStrips() && input->GetStrips()->GetNumberOfCells() > 0);
  if (!hasLines && hasSurface)
  {
    vtkErrorMacro("The input is a surface (it has polygons and no line cell): the scale-space image needs a curve, "
                  "a polyline or the points of a planar curve in order. Cut the surface first (Slice, vtkCutter) and "
                  "join the segments (vtkStripper).");
    return false;
  }
  const std::string why = vtkGLSCurve::Extract(input, this->Closed, state->Curve);
  if (!why.empty())
  {
    vtkErrorMacro("Invalid curve: " << why << ".");
    return false;
  }
  const vtkGLSCurve::Curve& curve = state->Curve;
  state->Arclength = gls::curveArclengths(curve.Points, curve.Closed);
  const double length = state->Arclength.back();
  if (!(length > 0.0))
  {
    vtkErrorMacro("Invalid curve: its length is zero (all " << curve.Ids.size() << " curve points coincide).");
    return false;
  }
  this->LastCurveClosed = curve.Closed;
  this->LastCurveLength = length;
  state->Columns = this->NumberOfArclengthSamples > 0 ? std::max(this->NumberOfArclengthSamples, 2)
                                                      : static_cast<int>(curve.Ids.size()) + (curve.Closed ? 1 : 0);
  run.Cloud = vtkGLSCloud();
  run.Cloud.Points = curve.Points;
  run.Cloud.Owned = curve.Ids.size();
  run.State = std::move(state);
  return true;
}

vtkGLSScaleFilterBase::SampleRequest vtkGLSScaleSpaceImage::GetSampleRequest(const vtkGLSRun& run) const
{
  const double n = static_cast<double>(run.Cloud.Owned);
  const int columns = static_cast<const CurveState&>(*run.State).Columns;
  SampleRequest request;
  request.BytesPerPointScale = 2 * sizeof(double) + 3 * sizeof(double) * columns / n;
  request.What = "the scale-space image (kappa and nu per curve point and scale, 3 image arrays)";
  request.Advice = "Use fewer scales or arclength samples.";
  return request;
}

bool vtkGLSScaleSpaceImage::ResolveScales(vtkGLSRun& run)
{
  // Linear from MinScale to MaxScale in ScaleUnits, or an equally spaced explicit list.
  run.Scales = this->ScaleList(run.Diagonal, LINEAR);
  const std::vector<double>& scales = run.Scales;
  if (scales.empty())
  {
    return false;
  }
  const std::size_t S = scales.size();
  const double step = S > 1 ? (scales.back() - scales.front()) / static_cast<double>(S - 1) : 1.0;
  for (std::size_t k = 0; k < S; ++k)
  {
    if (std::abs(scales[k] - (scales.front() + static_cast<double>(k) * step)) >
      1e-6 * (scales.back() - scales.front()))
    {
      vtkErrorMacro("Invalid scales: the explicit scales must be equally spaced (the image rows are equally "
                    "spaced in t); scale " << k << " is " << scales[k] << ", expected "
                                           << scales.front() + static_cast<double>(k) * step << ".");
      return false;
    }
  }
  return true;
}

bool vtkGLSScaleSpaceImage::GatherFitCloud(vtkGLSRun& run)
{
  const vtkGLSCurve::Curve& curve = static_cast<const CurveState&>(*run.State).Curve;
  vtkPointSet* input = run.Input;
  const std::size_t n = curve.Ids.size();
  std::string problem;
  bool absent = false;
  vtkDataArray* given = this->SelectNormals(0, input, problem, absent);
  if (!given && !absent)
  {
    vtkErrorMacro("Invalid normals: " << problem << ".");
    return false;
  }
  const double diagonal = gls::boundingDiagonal(curve.Points);
  const gls::PlaneFit plane = gls::fitPlane(curve.Points.data(), n);
  const bool planar = plane.maxDistance <= 1e-6 * diagonal;
  if (!given && !planar)
  {
    vtkErrorMacro("The input has no normals and the curve is not planar (a point lies "
      << plane.maxDistance << " from the best-fit plane, above 1e-6 of the diagonal " << diagonal
      << "): in-plane normals can only be computed for a planar curve. Give the curve oriented normals.");
    return false;
  }
  // Planar curves are fitted in their plane's coordinates (z = 0), others as given.
  std::vector<double>& points = run.Cloud.Points;
  std::vector<double>& normals = run.Cloud.Normals;
  normals.assign(3 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
  {
    if (planar)
    {
      gls::toPlaneFrame(plane, &curve.Points[3 * i], &points[3 * i], true);
      points[3 * i + 2] = 0.0;
    }
    if (given)
    {
      double nrm[3];
      given->GetTuple(curve.Ids[i], nrm);
      if (planar)
      {
        gls::toPlaneFrame(plane, nrm, &normals[3 * i], false);
        const double len = std::sqrt(vtkMath::Dot(nrm, nrm));
        if (std::abs(normals[3 * i + 2]) <= 1e-9 * len)
        {
          normals[3 * i + 2] = 0.0;
        }
      }
      else
      {
        std::copy(nrm, nrm + 3, &normals[3 * i]);
      }
    }
  }
  if (!given)
  {
    normals = gls::inPlaneCurveNormals(points, curve.Closed);
  }
  return true;
}

int vtkGLSScaleSpaceImage::ComputeOutputs(vtkGLSRun& run)
{
  const CurveState& state = static_cast<const CurveState&>(*run.State);
  const std::vector<double>& scales = run.Scales;
  const std::vector<double>& arclength = state.Arclength;
  const std::size_t n = state.Curve.Ids.size();
  const std::size_t S = scales.size();
  const double length = arclength.back();
  CurveSink sink(n, scales, this->Weights());
  if (!this->FeedSamples(run, sink, nullptr, 0.0, 0.85))
  {
    return ABORTED; // empty outputs
  }

  // Resample the curve points' values at uniformly spaced arclengths.
  vtkImageData* image = vtkImageData::GetData(run.OutputVector, 0);
  vtkPolyData* crossings = vtkPolyData::GetData(run.OutputVector, 1);
  const double step = S > 1 ? (scales.back() - scales.front()) / static_cast<double>(S - 1) : 1.0;
  const vtkIdType nx = state.Columns;
  const vtkIdType ny = static_cast<vtkIdType>(S);
  image->SetDimensions(static_cast<int>(nx), static_cast<int>(ny), 1);
  run.OutputVector->GetInformationObject(0)->Set(
    vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), image->GetExtent(), 6);
  image->SetOrigin(0.0, scales.front(), 0.0);
  image->SetSpacing(length / static_cast<double>(nx - 1), step, 1.0);
  auto kappa = NewArray(KappaName(), nx * ny);
  auto scaled = NewArray(ScaledKappaName, nx * ny);
  auto nu = NewArray(NuName, nx * ny);
  std::size_t segment = 0; // arclength[segment] <= s <= arclength[segment + 1]
  for (vtkIdType i = 0; i < nx; ++i)
  {
    const double s = i == nx - 1 ? length : length * static_cast<double>(i) / static_cast<double>(nx - 1);
    while (segment + 2 < arclength.size() && arclength[segment + 1] < s)
    {
      ++segment;
    }
    const double a = arclength[segment], b = arclength[segment + 1];
    const double w = b > a ? std::min(1.0, std::max(0.0, (s - a) / (b - a))) : 0.0;
    const std::size_t p0 = segment, p1 = (segment + 1) % n;
    for (vtkIdType k = 0; k < ny; ++k)
    {
      const std::size_t i0 = p0 * S + static_cast<std::size_t>(k), i1 = p1 * S + static_cast<std::size_t>(k);
      const auto lerp = [w](double v0, double v1) { return w == 0.0 ? v0 : (w == 1.0 ? v1 : v0 + w * (v1 - v0)); };
      const double kv = lerp(sink.Kappa[i0], sink.Kappa[i1]);
      const vtkIdType id = i + nx * k;
      kappa->SetValue(id, kv);
      scaled->SetValue(id, scales[static_cast<std::size_t>(k)] * kv);
      nu->SetValue(id, lerp(sink.Nu[i0], sink.Nu[i1]));
    }
  }
  image->GetPointData()->AddArray(kappa);
  image->GetPointData()->AddArray(nu);
  image->GetPointData()->SetScalars(scaled);
  WriteScales(image->GetFieldData(), scales);
  WriteRunFieldData(run, image->GetFieldData());
  this->UpdateProgress(0.9);
  if (this->GetAbortExecute())
  {
    image->Initialize();
    return ABORTED;
  }

  ZeroCrossings(image, crossings);
  WriteScales(crossings->GetFieldData(), scales);
  this->UpdateProgress(1.0);
  return COMPLETED;
}

void vtkGLSScaleSpaceImage::DescribeSettings(std::vector<SettingRange>& settings)
{
  this->Superclass::DescribeSettings(settings);
  settings.push_back({ "Closed", static_cast<double>(this->Closed), static_cast<double>(CLOSED_AUTO), static_cast<double>(CLOSED_YES) });
  settings.push_back({ "NumberOfArclengthSamples", static_cast<double>(this->NumberOfArclengthSamples), static_cast<double>(0), static_cast<double>(VTK_INT_MAX) });
}

void vtkGLSScaleSpaceImage::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Closed: " << this->Closed << "\n";
  os << indent << "NumberOfArclengthSamples: " << this->NumberOfArclengthSamples << "\n";
}
