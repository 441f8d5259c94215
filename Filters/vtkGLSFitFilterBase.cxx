#include "vtkGLSFitFilterBase.h"

#include "vtkGLSRun.h"

#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkPointSet.h"

#include "gls/Planarity.h"

#include <string>

vtkGLSFitFilterBase::vtkGLSFitFilterBase()
  : ScaleUnits(RELATIVE_TO_DIAGONAL)
  , MinimumNeighbors(0)
{
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::NORMALS);
}

vtkGLSFitFilterBase::~vtkGLSFitFilterBase() = default;

bool vtkGLSFitFilterBase::CheckFitParameters()
{
  if (this->MinimumNeighbors != 0 && this->MinimumNeighbors < 3)
  {
    vtkErrorMacro("MinimumNeighbors must be 0 (automatic) or at least 3, the fewest neighbours that determine a "
                  "fit (it is " << this->MinimumNeighbors << ").");
    return false;
  }
  return true;
}

double vtkGLSFitFilterBase::ToAbsoluteLength(const vtkGLSRun& run, double value) const
{
  return this->ScaleUnits == ABSOLUTE ? value : value * run.Diagonal;
}

bool vtkGLSFitFilterBase::GatherNormals(vtkGLSRun& run)
{
  const vtkIdType n = run.Input->GetNumberOfPoints();
  if (n < 1)
  {
    run.Cloud.Normals.clear(); // an empty piece of a distributed input (some rank has points)
    return true;
  }
  std::string problem;
  bool absent = false;
  vtkDataArray* nrm = this->SelectNormals(0, run.Input, problem, absent);
  if (!nrm)
  {
    vtkErrorMacro("Invalid normals: " << problem << ".");
    return false;
  }
  run.Cloud.Normals.resize(3 * static_cast<std::size_t>(n));
  CopyTriples(nrm, n, run.Cloud.Normals.data());
  run.NormalsName = nrm->GetName() ? nrm->GetName() : "";
  return true;
}

void vtkGLSFitFilterBase::ResolveMinimumNeighbors(vtkGLSRun& run) const
{
  if (this->MinimumNeighbors > 0)
  {
    run.MinimumNeighbors = this->MinimumNeighbors;
    return;
  }
  const gls::PlaneZ plane =
    gls::twoDimensionalFitInput(run.Cloud.Points.data(), run.Cloud.Normals.data(), run.Cloud.Owned);
  run.MinimumNeighbors = run.Distributed.AllInOnePlaneZ(plane.planar, plane.any, plane.z) ? 3.0 : 6.0;
}

bool vtkGLSFitFilterBase::AddGhosts(vtkGLSRun& run, double reach)
{
  std::size_t ghosts = 0;
  const bool ok = run.Distributed.AppendGhosts(
    run.Cloud.Points, run.Cloud.Owned, { { &run.Cloud.Normals, 3 } }, reach, ghosts);
  if (!run.Distributed.AllTrue(ok))
  {
    vtkErrorMacro("The exchange of ghost points between the processes failed.");
    return false;
  }
  run.GhostPoints = static_cast<long long>(ghosts);
  return true;
}

void vtkGLSFitFilterBase::DescribeSettings(std::vector<SettingRange>& settings)
{
  this->Superclass::DescribeSettings(settings);
  settings.push_back({ "ScaleUnits", static_cast<double>(this->ScaleUnits), static_cast<double>(ABSOLUTE), static_cast<double>(RELATIVE_TO_DIAGONAL) });
}

void vtkGLSFitFilterBase::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ScaleUnits: " << (this->ScaleUnits == ABSOLUTE ? "Absolute" : "RelativeToDiagonal") << "\n";
  os << indent << "MinimumNeighbors: " << this->MinimumNeighbors << "\n";
}
