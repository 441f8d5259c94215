#include "vtkGLSFilterBase.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSRun.h"

#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include <cmath>

vtkGLSFilterBase::vtkGLSFilterBase()
  : NumberOfThreads(0)
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkGLSFilterBase::~vtkGLSFilterBase()
{
  this->SetController(nullptr);
}

vtkCxxSetObjectMacro(vtkGLSFilterBase, Controller, vtkMultiProcessController);

int vtkGLSFilterBase::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkGLSFilterBase::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkGLSRun run(this->Controller);
  run.Input = vtkPolyData::GetData(inputVector[0]);
  run.OutputVector = outputVector;
  this->PrepareOutputs(run);
  if (!this->BeginRun(run))
  {
    return 0;
  }
  if (run.Idle)
  {
    return 1;
  }
  return this->Execute(run) == FAILED ? 0 : 1;
}

void vtkGLSFilterBase::PrepareOutputs(vtkGLSRun& run)
{
  run.Output = vtkPolyData::GetData(run.OutputVector);
  run.Output->ShallowCopy(run.Input);
  vtkNew<vtkFieldData> fd;
  fd->ShallowCopy(run.Input->GetFieldData());
  run.Output->SetFieldData(fd);
}

bool vtkGLSFilterBase::DistributeRun(vtkGLSRun&)
{
  return true;
}

bool vtkGLSFilterBase::BeginRun(vtkGLSRun& run)
{
  if (!this->DistributeRun(run))
  {
    return false;
  }
  if (run.Idle)
  {
    return true;
  }
  const vtkGLSDistributedCloud& dist = run.Distributed;
  vtkPolyData* input = run.Input;
  const vtkIdType n = input ? input->GetNumberOfPoints() : 0;
  std::vector<double>& xyz = run.Cloud.Points;
  xyz.resize(3 * static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    input->GetPoint(i, &xyz[3 * i]);
  }
  run.Cloud.Owned = static_cast<std::size_t>(n);
  // Every rank takes part, an empty piece too: the bounds are those of the finite points of all the pieces.
  run.HasFinitePoints = dist.FiniteBounds(xyz.data(), static_cast<std::size_t>(n), run.Bounds);
  if (run.HasFinitePoints)
  {
    const double dx = run.Bounds[1] - run.Bounds[0], dy = run.Bounds[3] - run.Bounds[2],
                 dz = run.Bounds[5] - run.Bounds[4];
    run.Diagonal = std::sqrt(dx * dx + dy * dy + dz * dz);
  }
  if (!(dist.Sum(static_cast<double>(n)) > 0.0))
  {
    if (dist.IsParallel())
    {
      vtkErrorMacro("The input has no points (on any of the " << dist.GetSize() << " processes).");
    }
    else
    {
      vtkErrorMacro("The input has no points.");
    }
    return false;
  }
  return true;
}

bool vtkGLSFilterBase::ReportProgress(double fraction, double begin, double end)
{
  this->UpdateProgress(begin + fraction * (end - begin));
  return this->GetAbortExecute() != 0;
}

vtkDataArray* vtkGLSFilterBase::FindSelectedNormals(int index, vtkPolyData* input)
{
  // A selection by name must be honoured; no selection means the active normals.
  const char* name = this->SelectedArrayName(index);
  return name ? input->GetPointData()->GetArray(name) : input->GetPointData()->GetNormals();
}

const char* vtkGLSFilterBase::SelectedArrayName(int index)
{
  vtkInformation* info = this->GetInputArrayInformation(index);
  const char* name = info && info->Has(vtkDataObject::FIELD_NAME()) ? info->Get(vtkDataObject::FIELD_NAME()) : nullptr;
  return name && name[0] != '\0' ? name : nullptr;
}

void vtkGLSFilterBase::WriteRunFieldData(const vtkGLSRun& run, vtkFieldData* fd)
{
  if (run.Distributed.IsParallel() && run.GhostPoints >= 0)
  {
    vtkNew<vtkIdTypeArray> ghosts;
    ghosts->SetName(vtkGLSArrayNames::GhostPoints);
    ghosts->InsertNextValue(static_cast<vtkIdType>(run.GhostPoints));
    fd->AddArray(ghosts);
  }
  if (!run.BackendUsed.empty())
  {
    vtkNew<vtkStringArray> backend;
    backend->SetName(vtkGLSArrayNames::Backend);
    backend->InsertNextValue(run.BackendUsed);
    fd->AddArray(backend);
  }
}

void vtkGLSFilterBase::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
}
