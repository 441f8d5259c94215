#include "vtkGLSScaleSpaceImage.h"

#include "vtkGLSDistributedCloud.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSCurve.h"

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

#include "gls/Descriptors.h"
#include "gls/ScaleSpaceEngine.h"

#include <algorithm>
#include <cmath>
#include <limits>

vtkStandardNewMacro(vtkGLSScaleSpaceImage);

namespace
{

constexpr const char* ScaledKappaName = "GLSScaledKappa";
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

/// Restores the scale parameters a RequestData overrides for its internal fit (without touching MTime).
struct ScaleParameterGuard
{
  ScaleParameterGuard(int& units, int& sampling, std::vector<double>& explicitScales)
    : Units(units)
    , Sampling(sampling)
    , Explicit(explicitScales)
    , SavedUnits(units)
    , SavedSampling(sampling)
    , SavedExplicit(explicitScales)
  {
  }
  ~ScaleParameterGuard()
  {
    this->Units = this->SavedUnits;
    this->Sampling = this->SavedSampling;
    this->Explicit = this->SavedExplicit;
  }
  int& Units;
  int& Sampling;
  std::vector<double>& Explicit;
  int SavedUnits;
  int SavedSampling;
  std::vector<double> SavedExplicit;
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
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkGLSArrayNames::Kappa);
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

} // namespace

vtkGLSScaleSpaceImage::vtkGLSScaleSpaceImage()
  : Closed(CLOSED_AUTO)
  , NumberOfArclengthSamples(0)
{
  this->NumberOfScales = 200;
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

int vtkGLSScaleSpaceImage::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkImageData" : "vtkPolyData");
  return 1;
}

int vtkGLSScaleSpaceImage::RequestInformation(
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

int vtkGLSScaleSpaceImage::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkImageData* image = vtkImageData::GetData(outputVector, 0);
  vtkPolyData* crossings = vtkPolyData::GetData(outputVector, 1);
  this->LastBackendUsed.clear();
  const vtkGLSDistributedCloud distributed(this->Controller);
  if (distributed.IsParallel())
  {
    // A curve is not cut into pieces: the one rank that holds it (a source that ignores piece requests gives it
    // all to rank 0) computes the image as a serial run; the other ranks give empty outputs.
    const vtkIdType local = input ? input->GetNumberOfPoints() : 0;
    const double holders = distributed.Sum(local > 0 ? 1.0 : 0.0);
    if (holders != 1.0)
    {
      vtkErrorMacro("In a distributed run the curve must be on one process; "
        << holders << " of the " << distributed.GetSize() << " processes hold points.");
      return 0;
    }
    if (local == 0)
    {
      return 1;
    }
    vtkMultiProcessController* controller = this->Controller; // kept registered: set back below
    this->Controller = nullptr;
    const int result = this->RequestData(request, inputVector, outputVector);
    this->Controller = controller;
    return result;
  }
  if (!input || input->GetNumberOfPoints() < 1)
  {
    vtkErrorMacro("The input has no points.");
    return 0;
  }

  // The ordered curve.
  vtkGLSCurve::Curve curve;
  const std::string why = vtkGLSCurve::Extract(input, this->Closed, curve);
  if (!why.empty())
  {
    vtkErrorMacro("Invalid curve: " << why << ".");
    return 0;
  }
  const std::size_t n = curve.Ids.size();
  const std::vector<double> arclength = vtkGLSCurve::Arclengths(curve.Points, curve.Closed);
  const double length = arclength.back();
  if (!(length > 0.0))
  {
    vtkErrorMacro("Invalid curve: its length is zero (all " << n << " curve points coincide).");
    return 0;
  }
  this->LastCurveClosed = curve.Closed;
  this->LastCurveLength = length;

  // Scales: linear from MinScale to MaxScale in ScaleUnits, or an equally spaced explicit list.
  ScaleParameterGuard guard(this->ScaleUnits, this->ScaleSampling, this->ExplicitScales);
  this->ScaleSampling = LINEAR;
  std::vector<double> scales = this->ComputeAbsoluteScales(input);
  if (scales.empty())
  {
    return 0;
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
      return 0;
    }
  }

  // Points and normals of the fit: planar curves in their plane's coordinates (z = 0), others as given.
  vtkDataArray* given = this->FindSelectedNormals(input);
  if (given && (given->GetNumberOfComponents() != 3 || given->GetNumberOfTuples() != input->GetNumberOfPoints()))
  {
    vtkErrorMacro("The normals array '" << (given->GetName() ? given->GetName() : "(unnamed)") << "' has "
                                        << given->GetNumberOfComponents() << " components and "
                                        << given->GetNumberOfTuples() << " tuples; expected 3 components and "
                                        << input->GetNumberOfPoints() << " tuples (one per point).");
    return 0;
  }
  const double diagonal = vtkGLSCurve::Diagonal(curve.Points);
  const vtkGLSCurve::Plane plane = vtkGLSCurve::FitPlane(curve.Points);
  const bool planar = plane.MaxDistance <= 1e-6 * diagonal;
  if (!given && !planar)
  {
    vtkErrorMacro("The input has no normals and the curve is not planar (a point lies "
      << plane.MaxDistance << " from the best-fit plane, above 1e-6 of the diagonal " << diagonal
      << "): in-plane normals can only be computed for a planar curve. Give the curve oriented normals.");
    return 0;
  }
  std::vector<double> fitPoints(3 * n), fitNormals(3 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    if (planar)
    {
      vtkGLSCurve::ToPlane(plane, &curve.Points[3 * i], &fitPoints[3 * i], true);
      fitPoints[3 * i + 2] = 0.0;
    }
    else
    {
      std::copy(&curve.Points[3 * i], &curve.Points[3 * i] + 3, &fitPoints[3 * i]);
    }
    if (given)
    {
      double nrm[3];
      given->GetTuple(curve.Ids[i], nrm);
      if (planar)
      {
        vtkGLSCurve::ToPlane(plane, nrm, &fitNormals[3 * i], false);
        const double len = std::sqrt(vtkMath::Dot(nrm, nrm));
        if (std::abs(fitNormals[3 * i + 2]) <= 1e-9 * len)
        {
          fitNormals[3 * i + 2] = 0.0;
        }
      }
      else
      {
        std::copy(nrm, nrm + 3, &fitNormals[3 * i]);
      }
    }
  }
  if (!given)
  {
    fitNormals = vtkGLSCurve::InPlaneNormals(fitPoints, curve.Closed);
  }

  // The internal cloud the base class fits, at the absolute scales computed above.
  vtkNew<vtkPolyData> cloud;
  vtkNew<vtkPoints> cloudPoints;
  cloudPoints->SetDataTypeToDouble();
  cloudPoints->SetNumberOfPoints(static_cast<vtkIdType>(n));
  vtkNew<vtkDoubleArray> cloudNormals;
  cloudNormals->SetName(given && given->GetName() ? given->GetName() : vtkGLSArrayNames::Normals);
  cloudNormals->SetNumberOfComponents(3);
  cloudNormals->SetNumberOfTuples(static_cast<vtkIdType>(n));
  for (std::size_t i = 0; i < n; ++i)
  {
    cloudPoints->SetPoint(static_cast<vtkIdType>(i), &fitPoints[3 * i]);
    cloudNormals->SetTuple(static_cast<vtkIdType>(i), &fitNormals[3 * i]);
  }
  cloud->SetPoints(cloudPoints);
  cloud->GetPointData()->SetNormals(cloudNormals);
  this->ScaleUnits = ABSOLUTE;
  this->ExplicitScales = scales;
  const int columns = this->NumberOfArclengthSamples > 0 ? std::max(this->NumberOfArclengthSamples, 2)
                                                         : static_cast<int>(n) + (curve.Closed ? 1 : 0);
  OutputCost cost;
  cost.BytesPerPointScale = 2 * sizeof(double) + 3 * sizeof(double) * columns / static_cast<double>(n);
  cost.What = "the scale-space image (kappa and nu per curve point and scale, 3 image arrays)";
  cost.Advice = "Use fewer scales or arclength samples.";
  std::vector<double> used;
  if (!this->PrepareScaleSamples(cloud, false, false, used, cost))
  {
    return 0;
  }
  CurveSink sink(n, scales, gls::VariationWeights{ this->WTau, this->WEta, this->WKappa });
  if (!this->RunScaleSamples(sink, nullptr, 0.0, 0.85))
  {
    return 1; // aborted: empty outputs
  }

  // Resample the curve points' values at uniformly spaced arclengths.
  const vtkIdType nx = columns;
  const vtkIdType ny = static_cast<vtkIdType>(S);
  image->SetDimensions(static_cast<int>(nx), static_cast<int>(ny), 1);
  outputVector->GetInformationObject(0)->Set(
    vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), image->GetExtent(), 6);
  image->SetOrigin(0.0, scales.front(), 0.0);
  image->SetSpacing(length / static_cast<double>(nx - 1), step, 1.0);
  auto kappa = NewArray(vtkGLSArrayNames::Kappa, nx * ny);
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
  StoreScales(image->GetFieldData(), scales);
  this->StoreBackend(image->GetFieldData());
  this->UpdateProgress(0.9);
  if (this->GetAbortExecute())
  {
    image->Initialize();
    return 1;
  }

  ZeroCrossings(image, crossings);
  StoreScales(crossings->GetFieldData(), scales);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkGLSScaleSpaceImage::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Closed: " << this->Closed << "\n";
  os << indent << "NumberOfArclengthSamples: " << this->NumberOfArclengthSamples << "\n";
}
