#include "vtkGLSScaleProfiles.h"

#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include "gls/Descriptors.h"
#include "gls/ScaleSpaceEngine.h"

#include <string>

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

int vtkGLSScaleProfiles::FillOutputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTable");
  return 1;
}

int vtkGLSScaleProfiles::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkTable* output = vtkTable::GetData(outputVector);
  const vtkIdType n = input->GetNumberOfPoints();
  if (n < 1)
  {
    vtkErrorMacro("The input has no points.");
    return 0;
  }
  if (this->PointIds.empty())
  {
    vtkErrorMacro("No point selected: AddPointId (PointIds in ParaView) names the points to profile.");
    return 0;
  }
  std::vector<std::uint64_t> ids;
  for (vtkIdType id : this->PointIds)
  {
    if (id < 0 || id >= n)
    {
      vtkErrorMacro("Point id " << id << " is out of range: the input has " << n << " points.");
      return 0;
    }
    ids.push_back(static_cast<std::uint64_t>(id));
  }
  std::vector<double> scales;
  if (!this->PrepareScaleSamples(input, true, true, scales))
  {
    return 0;
  }
  ProfileSink sink(ids, scales.size());
  if (!this->RunScaleSamples(sink, &ids))
  {
    return 1; // aborted: an empty table
  }

  const vtkIdType S = static_cast<vtkIdType>(scales.size());
  vtkNew<vtkDoubleArray> t;
  t->SetName("t");
  t->SetNumberOfTuples(S);
  for (vtkIdType k = 0; k < S; ++k)
  {
    t->SetValue(k, scales[static_cast<std::size_t>(k)]);
  }
  output->AddColumn(t);
  const gls::VariationWeights weights{ this->WTau, this->WEta, this->WKappa };
  for (std::size_t j = 0; j < ids.size(); ++j)
  {
    const std::string suffix = " (" + std::to_string(ids[j]) + ")";
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
      const gls::ScaleSample& s = sink.Samples[j * scales.size() + static_cast<std::size_t>(k)];
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
  return 1;
}

void vtkGLSScaleProfiles::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PointIds: " << this->PointIds.size() << "\n";
}
