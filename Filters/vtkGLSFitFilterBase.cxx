#include "vtkGLSFitFilterBase.h"

#include "vtkGLSRun.h"

#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkPointSet.h"

#include "gls/Planarity.h"

#include <unistd.h>

#include <string>

vtkGLSFitFilterBase::vtkGLSFitFilterBase()
  : ScaleUnits(RELATIVE_TO_DIAGONAL)
  , MinimumNeighbors(0)
  , MemoryBudget(0.0)
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

double vtkGLSFitFilterBase::MemoryBudgetBytes() const
{
  const double budget = this->MemoryBudget * 1024.0 * 1024.0;
  if (budget > 0.0)
  {
    return budget;
  }
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && pageSize > 0 ? 0.5 * static_cast<double>(pages) * static_cast<double>(pageSize) : 4e9;
}

bool vtkGLSFitFilterBase::CheckMemoryBudget(double needed, const char* what, const char* advice)
{
  const double budget = this->MemoryBudgetBytes();
  if (needed <= budget)
  {
    return true;
  }
  vtkErrorMacro("Not enough memory budget: " << what << " needs about " << needed / (1024.0 * 1024.0)
                                             << " MiB, above the budget of " << budget / (1024.0 * 1024.0)
                                             << " MiB (MemoryBudget; 0 = half of the physical memory). " << advice);
  return false;
}

bool vtkGLSFitFilterBase::AgreeToContinue(const vtkGLSRun& run, bool ok)
{
  if (run.Distributed.AllTrue(ok))
  {
    return true;
  }
  if (ok)
  {
    vtkErrorMacro("Stopped: another process of this distributed run failed (see its error).");
  }
  return false;
}

void vtkGLSFitFilterBase::DescribeSettings(std::vector<SettingRange>& settings)
{
  this->Superclass::DescribeSettings(settings);
  settings.push_back({ "ScaleUnits", static_cast<double>(this->ScaleUnits), static_cast<double>(ABSOLUTE), static_cast<double>(RELATIVE_TO_DIAGONAL) });
  settings.push_back({ "MemoryBudget", static_cast<double>(this->MemoryBudget), static_cast<double>(0.0), static_cast<double>(VTK_DOUBLE_MAX) });
}

void vtkGLSFitFilterBase::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ScaleUnits: " << (this->ScaleUnits == ABSOLUTE ? "Absolute" : "RelativeToDiagonal") << "\n";
  os << indent << "MinimumNeighbors: " << this->MinimumNeighbors << "\n";
  os << indent << "MemoryBudget (MiB): " << this->MemoryBudget << "\n";
}
