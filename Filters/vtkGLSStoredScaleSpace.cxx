#include "vtkGLSStoredScaleSpace.h"

#include "vtkGLSArrayNames.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <cmath>
#include <limits>

namespace
{

vtkDataArray* FindArray(vtkPolyData* input, const char* name, int components)
{
  vtkDataArray* a = input->GetPointData()->GetArray(name);
  if (a && a->GetNumberOfComponents() == components && a->GetNumberOfTuples() == input->GetNumberOfPoints())
  {
    return a;
  }
  return nullptr;
}

} // namespace

bool vtkGLSStoredScaleSpace::Bind(
  vtkPolyData* input, std::size_t scaleCount, bool needDescriptors, bool needDerivatives)
{
  const int S = static_cast<int>(scaleCount);
  this->ScaleCount = scaleCount;
  if (needDescriptors)
  {
    this->Tau = FindArray(input, vtkGLSArrayNames::Tau, S);
    this->Kappa = FindArray(input, vtkGLSArrayNames::Kappa, S);
    this->Fitness = FindArray(input, vtkGLSArrayNames::Fitness, S);
    if (!this->Tau || !this->Kappa || !this->Fitness)
    {
      return false;
    }
  }
  if (needDerivatives)
  {
    this->DTau = FindArray(input, vtkGLSArrayNames::DTau, S);
    this->DKappa = FindArray(input, vtkGLSArrayNames::DKappa, S);
    this->DEta = FindArray(input, vtkGLSArrayNames::DEta, 3 * S);
    if (!this->DTau || !this->DKappa || !this->DEta)
    {
      return false;
    }
  }
  return scaleCount > 0;
}

void vtkGLSStoredScaleSpace::Read(std::uint64_t pointId, gls::ScaleSample* out) const
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const vtkIdType id = static_cast<vtkIdType>(pointId);
  for (std::size_t k = 0; k < this->ScaleCount; ++k)
  {
    const int c = static_cast<int>(k);
    gls::ScaleSample& s = out[k];
    s.tau = this->Tau ? this->Tau->GetComponent(id, c) : nan;
    s.kappa = this->Kappa ? this->Kappa->GetComponent(id, c) : nan;
    s.phi = this->Fitness ? this->Fitness->GetComponent(id, c) : nan;
    s.dtau = this->DTau ? this->DTau->GetComponent(id, c) : nan;
    s.dkappa = this->DKappa ? this->DKappa->GetComponent(id, c) : nan;
    s.deta = this->DEta ? gls::Vec3{ this->DEta->GetComponent(id, 3 * c), this->DEta->GetComponent(id, 3 * c + 1),
                                      this->DEta->GetComponent(id, 3 * c + 2) }
                        : gls::Vec3{ nan, nan, nan };
    s.eta = { nan, nan, nan };
    s.neighbors = nan;
    bool valid = true;
    if (this->Tau)
    {
      valid = valid && std::isfinite(s.tau) && std::isfinite(s.kappa) && std::isfinite(s.phi);
    }
    if (this->DTau)
    {
      valid = valid && std::isfinite(s.dtau) && std::isfinite(s.dkappa) && std::isfinite(s.deta.x) &&
        std::isfinite(s.deta.y) && std::isfinite(s.deta.z);
    }
    s.valid = valid;
  }
}
