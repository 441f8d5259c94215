#include "vtkGLSFilterBase.h"

#include "vtkGLSArrayNames.h"
#include "vtkGLSRun.h"

#include "gls/StrayPoints.h"

#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkAOSDataArrayTemplate.h"
#include "vtkDataArray.h"
#include "vtkDataObjectTreeIterator.h"
#include "vtkDataObjectTypes.h"
#include "vtkDataSetAttributes.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkDoubleArray.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include <sstream>
#include <unistd.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <vector>

namespace
{

double DiagonalOf(const double b[6])
{
  const double dx = b[1] - b[0], dy = b[3] - b[2], dz = b[5] - b[4];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

bool NameSaysNormals(const char* name)
{
  std::string lower = name ? name : "";
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  return lower.find("normal") != std::string::npos || lower.find("nrm") != std::string::npos;
}

bool IsFloatingVector(vtkDataArray* a)
{
  return a && a->GetNumberOfComponents() == 3 && (a->GetDataType() == VTK_FLOAT || a->GetDataType() == VTK_DOUBLE);
}

/// The leaves of a composite dataset, empty ones included (every rank of a distributed run visits the same ones).
vtkSmartPointer<vtkCompositeDataIterator> Leaves(vtkCompositeDataSet* composite)
{
  vtkSmartPointer<vtkCompositeDataIterator> it;
  it.TakeReference(composite->NewIterator());
  it->SkipEmptyNodesOff();
  if (auto* tree = vtkDataObjectTreeIterator::SafeDownCast(it))
  {
    tree->VisitOnlyLeavesOn();
    tree->TraverseSubTreeOn();
  }
  return it;
}

}

vtkGLSFilterBase::vtkGLSFilterBase()
  : NumberOfThreads(0)
  , MemoryBudget(0.0)
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
  // The composite type first: the composite pipeline looks at the first type only to decide whether to iterate
  // over the blocks itself (this filter iterates, with the whole composite's diagonal).
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

int vtkGLSFilterBase::FillOutputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkDataObject");
  return 1;
}

int vtkGLSFilterBase::RequestDataObject(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  if (!input)
  {
    return 0;
  }
  vtkInformation* info = outputVector->GetInformationObject(0);
  vtkDataObject* output = info->Get(vtkDataObject::DATA_OBJECT());
  if (!output || !output->IsA(input->GetClassName()))
  {
    vtkDataObject* made = input->NewInstance();
    info->Set(vtkDataObject::DATA_OBJECT(), made);
    made->Delete();
  }
  return 1;
}

int vtkGLSFilterBase::MakeDeclaredOutputs(vtkInformationVector* outputVector)
{
  for (int port = 0; port < this->GetNumberOfOutputPorts(); ++port)
  {
    const char* type = this->GetOutputPortInformation(port)->Get(vtkDataObject::DATA_TYPE_NAME());
    vtkInformation* info = outputVector->GetInformationObject(port);
    vtkDataObject* output = info->Get(vtkDataObject::DATA_OBJECT());
    if (!output || !output->IsA(type))
    {
      vtkDataObject* made = vtkDataObjectTypes::NewDataObject(type);
      if (!made)
      {
        return 0;
      }
      info->Set(vtkDataObject::DATA_OBJECT(), made);
      made->Delete();
    }
  }
  return 1;
}

void vtkGLSFilterBase::DescribeSettings(std::vector<SettingRange>& settings)
{
  settings.push_back({ "NumberOfThreads", static_cast<double>(this->NumberOfThreads), 0.0, 1024.0 });
  settings.push_back({ "MemoryBudget", this->MemoryBudget, 0.0, VTK_DOUBLE_MAX });
}

double vtkGLSFilterBase::MemoryBudgetBytes() const
{
  const double budget = this->MemoryBudget * 1024.0 * 1024.0;
  if (budget > 0.0)
  {
    return budget;
  }
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && pageSize > 0 ? 0.5 * static_cast<double>(pages) * static_cast<double>(pageSize) : 4e9;
}

bool vtkGLSFilterBase::AgreeToContinue(const vtkGLSRun& run, bool ok)
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

bool vtkGLSFilterBase::CheckMemoryBudget(double needed, const char* what, const char* advice)
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

double vtkGLSFilterBase::GetSettingMinimum(const char* name)
{
  return this->SettingBound(name, false);
}

double vtkGLSFilterBase::GetSettingMaximum(const char* name)
{
  return this->SettingBound(name, true);
}

double vtkGLSFilterBase::SettingBound(const char* name, bool maximum)
{
  std::vector<SettingRange> settings;
  this->DescribeSettings(settings);
  for (const SettingRange& s : settings)
  {
    if (name && std::strcmp(s.Name, name) == 0)
    {
      return maximum ? s.Maximum : s.Minimum;
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

bool vtkGLSFilterBase::ValidateSettings()
{
  std::vector<SettingRange> settings;
  this->DescribeSettings(settings);
  for (const SettingRange& s : settings)
  {
    if (s.Value >= s.Minimum && s.Value <= s.Maximum)
    {
      continue;
    }
    std::ostringstream range;
    if (s.Maximum >= VTK_INT_MAX)
    {
      range << "at least " << s.Minimum;
    }
    else
    {
      range << "from " << s.Minimum << " to " << s.Maximum;
    }
    vtkErrorMacro("Invalid " << s.Name << ": " << s.Value << " (allowed: " << range.str()
                             << "). Nothing was computed.");
    return false;
  }
  return true;
}

int vtkGLSFilterBase::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  int ok = 0;
  if (!this->ValidateSettings())
  {
    ok = 0;
  }
  else if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
  {
    ok = this->RunOnBlocks(composite, outputVector);
  }
  else
  {
    ok = this->RunOn(vtkPointSet::SafeDownCast(input), outputVector,
      outputVector->GetInformationObject(0)->Get(vtkDataObject::DATA_OBJECT()), 0.0);
  }
  if (!ok)
  {
    // A failed filter gives empty outputs, the VTK way: nothing downstream runs on stale data.
    for (int port = 0; port < this->GetNumberOfOutputPorts(); ++port)
    {
      if (vtkDataObject* o = outputVector->GetInformationObject(port)->Get(vtkDataObject::DATA_OBJECT()))
      {
        o->Initialize();
      }
    }
  }
  return ok;
}

int vtkGLSFilterBase::RunOn(
  vtkPointSet* input, vtkInformationVector* outputVector, vtkDataObject* blockOutput, double diagonal)
{
  if (!input)
  {
    vtkErrorMacro("The input is not a point set.");
    return 0;
  }
  vtkGLSRun run(this->Controller);
  run.Input = input;
  run.OutputVector = outputVector;
  run.OutputObject = blockOutput;
  this->PrepareOutputs(run);
  if (!this->BeginRun(run))
  {
    return 0;
  }
  if (run.Idle)
  {
    return 1;
  }
  if (diagonal > 0.0)
  {
    run.Diagonal = diagonal;
  }
  if (this->Execute(run) == FAILED)
  {
    return 0;
  }
  if (run.AnyStray && run.Output)
  {
    // Which points were left out as stray: a picture or a later step can leave them out too (on every rank of a
    // distributed run where some piece had one, so that the pieces carry the same arrays).
    vtkNew<vtkUnsignedCharArray> stray;
    stray->SetName(vtkGLSArrayNames::Stray);
    stray->SetNumberOfTuples(run.Output->GetNumberOfPoints());
    stray->FillValue(0);
    for (std::uint64_t i : run.StrayIds)
    {
      stray->SetValue(static_cast<vtkIdType>(i), 1);
    }
    run.Output->GetPointData()->AddArray(stray);
  }
  return 1;
}

int vtkGLSFilterBase::RunOnBlocks(vtkCompositeDataSet* input, vtkInformationVector* outputVector)
{
  vtkCompositeDataSet* output = vtkCompositeDataSet::GetData(outputVector, 0);
  if (!output)
  {
    vtkErrorMacro("The output of a composite input must be a composite dataset.");
    return 0;
  }
  output->CopyStructure(input);
  const vtkGLSDistributedCloud dist(this->Controller);
  double diagonal = 0.0;
  if (!this->CompositeDiagonal(input, dist, diagonal))
  {
    return 0;
  }
  // The blocks as point sets (an empty one stands for a missing block: it still takes part in a distributed run).
  std::vector<vtkSmartPointer<vtkPointSet>> blocks;
  std::vector<bool> present;
  auto it = Leaves(input);
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    vtkSmartPointer<vtkPointSet> block = vtkPointSet::SafeDownCast(it->GetCurrentDataObject());
    present.push_back(block != nullptr);
    blocks.push_back(block ? block : vtkSmartPointer<vtkPointSet>(vtkSmartPointer<vtkPolyData>::New()));
  }
  std::vector<std::size_t> order(blocks.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  if (!this->BeginComposite(blocks, diagonal, order))
  {
    this->EndComposite();
    return 0;
  }
  std::vector<vtkSmartPointer<vtkDataObject>> outputs(blocks.size());
  int computed = 0;
  int result = this->RunBlocksInOrder(dist, blocks, order, outputVector, diagonal, outputs, computed);
  std::size_t leaf = 0;
  for (it->InitTraversal(); !it->IsDoneWithTraversal() && result; it->GoToNextItem(), ++leaf)
  {
    if (present[leaf])
    {
      output->SetDataSet(it, outputs[leaf]);
    }
  }
  this->EndComposite();
  if (result && computed == 0)
  {
    vtkErrorMacro("The input has no points (none of its blocks has any).");
    return 0;
  }
  return result;
}

bool vtkGLSFilterBase::CompositeDiagonal(
  vtkCompositeDataSet* input, const vtkGLSDistributedCloud& dist, double& diagonal)
{
  // Every block must be a point set (or empty); lengths are relative to the whole composite's diagonal.
  std::vector<double> xyz;
  bool ok = true;
  auto it = Leaves(input);
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    vtkDataObject* leaf = it->GetCurrentDataObject();
    auto* points = vtkPointSet::SafeDownCast(leaf);
    if (leaf && !points)
    {
      vtkErrorMacro("Block " << it->GetCurrentFlatIndex() << " is a " << leaf->GetClassName()
                             << ", not a point set: GLS filters take point clouds, meshes and other vtkPointSets.");
      ok = false;
      break;
    }
    for (vtkIdType i = 0; points && i < points->GetNumberOfPoints(); ++i)
    {
      double p[3];
      points->GetPoint(i, p);
      xyz.insert(xyz.end(), p, p + 3);
    }
  }
  if (!dist.AllTrue(ok))
  {
    return false;
  }
  std::vector<std::uint64_t> stray;
  if (!BlankStrayPoints(dist, xyz, stray)) // the blocks' runs leave them out too: the diagonal of one block of it all
  {
    return false;
  }
  double bounds[6];
  diagonal = dist.FiniteBounds(xyz.data(), xyz.size() / 3, bounds) ? DiagonalOf(bounds) : 0.0;
  return true;
}

int vtkGLSFilterBase::RunBlocksInOrder(const vtkGLSDistributedCloud& dist,
  const std::vector<vtkSmartPointer<vtkPointSet>>& blocks, const std::vector<std::size_t>& order,
  vtkInformationVector* outputVector, double diagonal, std::vector<vtkSmartPointer<vtkDataObject>>& outputs,
  int& computed)
{
  int result = 1;
  for (std::size_t k = 0; k < order.size() && result; ++k)
  {
    vtkPointSet* block = blocks[order[k]];
    vtkSmartPointer<vtkDataObject>& blockOutput = outputs[order[k]];
    blockOutput.TakeReference(block->NewInstance());
    if (dist.Sum(static_cast<double>(block->GetNumberOfPoints())) > 0.0)
    {
      ++computed;
      result = this->RunOn(block, outputVector, blockOutput, diagonal);
    }
    else
    {
      blockOutput->ShallowCopy(block); // a block without points (on every process) passes through
    }
  }
  return result;
}

bool vtkGLSFilterBase::BeginComposite(
  const std::vector<vtkSmartPointer<vtkPointSet>>&, double, std::vector<std::size_t>&)
{
  return true;
}

void vtkGLSFilterBase::EndComposite() {}

void vtkGLSFilterBase::PrepareOutputs(vtkGLSRun& run)
{
  run.Output = vtkPointSet::SafeDownCast(run.OutputObject);
  run.Output->ShallowCopy(run.Input);
  vtkNew<vtkFieldData> fd;
  fd->ShallowCopy(run.Input->GetFieldData());
  run.Output->SetFieldData(fd);
}

bool vtkGLSFilterBase::DistributeRun(vtkGLSRun&)
{
  return true;
}

void vtkGLSFilterBase::CopyTriples(vtkDataArray* triples, vtkIdType n, double* out)
{
  // A 10M-point cloud: 0.16 s through GetTuple, a few hundredths as one copy.
  if (auto* doubles = vtkAOSDataArrayTemplate<double>::FastDownCast(triples))
  {
    const double* first = doubles->GetPointer(0);
    std::copy(first, first + 3 * n, out);
    return;
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    triples->GetTuple(i, out + 3 * i);
  }
}

bool vtkGLSFilterBase::BlankStrayPoints(
  const vtkGLSDistributedCloud& dist, std::vector<double>& xyz, std::vector<std::uint64_t>& stray)
{
  if (!dist.StrayPoints(xyz.data(), xyz.size() / 3, stray))
  {
    return false;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::uint64_t i : stray)
  {
    xyz[3 * i] = xyz[3 * i + 1] = xyz[3 * i + 2] = nan;
  }
  return true;
}

void vtkGLSFilterBase::LeaveOutNonFinitePoints(vtkGLSRun& run)
{
  std::vector<double>& xyz = run.Cloud.Points;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  long long count = 0;
  for (std::size_t i = 0; i < run.Cloud.Owned; ++i)
  {
    double* p = xyz.data() + 3 * i;
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])))
    {
      p[0] = p[1] = p[2] = nan; // one rule for NaN and infinite rows: in no neighbourhood, no bound
      ++count;
    }
  }
  run.NonFinitePoints = count;
  const double all = run.Distributed.Sum(static_cast<double>(count));
  if (all > 0.0 && run.Distributed.GetRank() == 0)
  {
    const double total = run.Distributed.Sum(static_cast<double>(run.Cloud.Owned));
    vtkWarningMacro(<< static_cast<long long>(all) << " of the " << static_cast<long long>(total)
                    << " input points have a non-finite coordinate (missing returns of a scanner: NaN or "
                       "infinite): left out of every neighbourhood and of the bounds, their results NaN. Field data "
                       "GLSNonFinitePoints counts them (those of this process's piece in a distributed run).");
  }
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
  vtkPointSet* input = run.Input;
  const vtkIdType n = input ? input->GetNumberOfPoints() : 0;
  std::vector<double>& xyz = run.Cloud.Points;
  xyz.resize(3 * static_cast<std::size_t>(n));
  if (n > 0)
  {
    CopyTriples(input->GetPoints()->GetData(), n, xyz.data());
  }
  run.Cloud.Owned = static_cast<std::size_t>(n);
  this->LeaveOutNonFinitePoints(run);
  if (!BlankStrayPoints(dist, xyz, run.StrayIds))
  {
    vtkErrorMacro("The search for stray points failed to communicate between the processes.");
    return false;
  }
  const double strays = dist.Sum(static_cast<double>(run.StrayIds.size()));
  run.AnyStray = strays > 0.0;
  if (run.AnyStray && dist.GetRank() == 0)
  {
    std::ostringstream first;
    if (!dist.IsParallel())
    {
      first << "; the first: point " << run.StrayIds.front();
    }
    vtkWarningMacro(<< strays << " stray point" << (strays > 1.0 ? "s" : "")
                    << " (far outside the rest of the cloud, with no other point near" << first.str()
                    << ") left out: NaN results, in no neighbourhood, and the bounding box (the relative "
                       "scales) is that of the other points. Field data GLSStrayPoints counts them (those of "
                       "this process's piece in a distributed run), the point array GLSStray marks them.");
  }
  // Every rank takes part, an empty piece too: the bounds are those of the finite points of all the pieces.
  run.HasFinitePoints = dist.FiniteBounds(xyz.data(), static_cast<std::size_t>(n), run.Bounds);
  if (run.HasFinitePoints)
  {
    run.Diagonal = DiagonalOf(run.Bounds);
    // The coordinates from the bounds' low corner (the same on every process; NaN rows stay NaN).
    for (int a = 0; a < 3; ++a)
    {
      run.Cloud.Anchor[a] = run.Bounds[2 * a];
    }
    for (std::size_t i = 0; i < xyz.size(); ++i)
    {
      xyz[i] -= run.Cloud.Anchor[i % 3];
    }
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

bool vtkGLSFilterBase::Heartbeat()
{
  this->UpdateProgress(this->GetProgress());
  return this->GetAbortExecute() != 0;
}

bool vtkGLSFilterBase::ReportProgress(double fraction, double begin, double end)
{
  this->UpdateProgress(begin + fraction * (end - begin));
  return this->GetAbortExecute() != 0;
}

vtkDataArray* vtkGLSFilterBase::SelectNormals(
  int index, vtkDataSet* input, std::string& problem, bool& absent, const char* what)
{
  absent = false;
  vtkPointData* pd = input->GetPointData();
  const vtkIdType n = input->GetNumberOfPoints();
  const char* name = this->SelectedArrayName(index);
  if (name)
  {
    // A selection by name is honoured, and must be normals-shaped.
    vtkDataArray* a = pd->GetArray(name);
    if (!a)
    {
      problem = std::string("the selected ") + what + " array '" + name + "' is not a point array of the input";
      return nullptr;
    }
    if (a->GetNumberOfComponents() != 3 || a->GetNumberOfTuples() != n)
    {
      problem = std::string("the ") + what + " array '" + name + "' has " + std::to_string(a->GetNumberOfComponents()) +
        " components and " + std::to_string(a->GetNumberOfTuples()) + " tuples; expected 3 components and " +
        std::to_string(n) + " tuples (one per point)";
      return nullptr;
    }
    if (!IsFloatingVector(a))
    {
      problem = std::string("the selected ") + what + " array '" + name + "' holds " + a->GetDataTypeAsString() +
        " values (colours or labels?): " + what + " arrays are floating-point; select a float or double array";
      return nullptr;
    }
    return a;
  }
  vtkDataArray* active = pd->GetNormals();
  if (IsFloatingVector(active) && active->GetNumberOfTuples() == n)
  {
    return active;
  }
  std::vector<vtkDataArray*> candidates, named;
  for (int i = 0; i < pd->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* a = pd->GetArray(i);
    if (IsFloatingVector(a) && a->GetNumberOfTuples() == n)
    {
      candidates.push_back(a);
      if (NameSaysNormals(a->GetName()))
      {
        named.push_back(a);
      }
    }
  }
  if (named.size() == 1)
  {
    return named.front();
  }
  const std::vector<vtkDataArray*>& listed = named.empty() ? candidates : named;
  std::string names;
  for (vtkDataArray* a : listed)
  {
    names += std::string(names.empty() ? "" : ", ") + "'" + (a->GetName() ? a->GetName() : "(unnamed)") + "'";
  }
  if (candidates.empty())
  {
    absent = true;
    problem = "the input has no normals (no floating-point 3-component point array): set active normals, or run "
              "vtkGLSNormalEstimation (GLS Normal Estimation) first";
  }
  else if (named.empty() && candidates.size() == 1)
  {
    problem = "the input has no active normals and its only floating-point 3-component point array, " + names +
      ", is not named as normals: select it as the normals (SetInputArrayToProcess(0, ...), Normals in ParaView) "
      "if it holds them, or run vtkGLSNormalEstimation (GLS Normal Estimation) first";
  }
  else
  {
    problem = "the input has no active normals and several point arrays could be the normals (" + names +
      "): select one (SetInputArrayToProcess(0, ...), Normals in ParaView)";
  }
  return nullptr;
}

void vtkGLSFilterBase::WarnAboutNormalLengths(
  const vtkGLSRun& run, const std::vector<double>& normals, const char* name)
{
  double off = 0.0, lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (std::size_t i = 0; i + 2 < normals.size(); i += 3)
  {
    const double len = std::sqrt(normals[i] * normals[i] + normals[i + 1] * normals[i + 1] + normals[i + 2] * normals[i + 2]);
    if (len > 0.0 && std::isfinite(len) && std::abs(len - 1.0) > 1e-3)
    {
      off += 1.0;
      lo = std::min(lo, len);
      hi = std::max(hi, len);
    }
  }
  const vtkGLSDistributedCloud& dist = run.Distributed;
  off = dist.Sum(off);
  lo = dist.Min(lo);
  hi = dist.Max(hi);
  if (off > 0.0 && dist.GetRank() == 0)
  {
    vtkWarningMacro(<< static_cast<long long>(off) << " normals of '" << (name ? name : "(unnamed)")
                    << "' have lengths far from 1 (from " << lo << " to " << hi
                    << "): they are normalized; if that array does not hold normals, select another.");
  }
}

const char* vtkGLSFilterBase::SelectedArrayName(int index)
{
  vtkInformation* info = this->GetInputArrayInformation(index);
  const char* name = info && info->Has(vtkDataObject::FIELD_NAME()) ? info->Get(vtkDataObject::FIELD_NAME()) : nullptr;
  if (!name || name[0] == '\0' || std::strcmp(name, vtkGLSArrayNames::AutomaticArray) == 0)
  {
    return nullptr;
  }
  return name;
}

void vtkGLSFilterBase::MergeCoincidentPoints(vtkGLSRun& run)
{
  this->Heartbeat();
  this->NoteCoincidentPoints(run, run.Cloud.MergeCoincident(this->NumberOfThreads));
  this->Heartbeat();
}

void vtkGLSFilterBase::NoteCoincidentPoints(vtkGLSRun& run, std::size_t merged)
{
  const vtkGLSDistributedCloud& dist = run.Distributed;
  run.CoincidentPoints = static_cast<long long>(merged);
  const double all = dist.Sum(static_cast<double>(merged));
  const double total = dist.Sum(static_cast<double>(run.Input->GetNumberOfPoints()));
  if (all > 0.0 && dist.GetRank() == 0)
  {
    vtkWarningMacro(<< static_cast<long long>(all) << " of the " << static_cast<long long>(total)
                    << " input points coincide with another one (the same coordinates): each position is computed "
                       "and counted once, and its results are written to every copy.");
  }
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
  if (!run.StrayIds.empty())
  {
    vtkNew<vtkIdTypeArray> stray;
    stray->SetName(vtkGLSArrayNames::StrayPoints);
    stray->InsertNextValue(static_cast<vtkIdType>(run.StrayIds.size()));
    fd->AddArray(stray);
  }
  if (run.MinimumNeighbors > 0.0)
  {
    vtkNew<vtkDoubleArray> minimum;
    minimum->SetName(vtkGLSArrayNames::MinimumNeighbors);
    minimum->InsertNextValue(run.MinimumNeighbors);
    fd->AddArray(minimum);
  }
  if (run.TilesUsed > 1)
  {
    vtkNew<vtkIdTypeArray> tiles;
    tiles->SetName(vtkGLSArrayNames::Tiles);
    tiles->InsertNextValue(static_cast<vtkIdType>(run.TilesUsed));
    fd->AddArray(tiles);
  }
  if (run.CompactNormals)
  {
    vtkNew<vtkIdTypeArray> compact;
    compact->SetName(vtkGLSArrayNames::CompactNormals);
    compact->InsertNextValue(1);
    fd->AddArray(compact);
  }
  if (run.NonFinitePoints > 0)
  {
    vtkNew<vtkIdTypeArray> nonFinite;
    nonFinite->SetName(vtkGLSArrayNames::NonFinitePoints);
    nonFinite->InsertNextValue(static_cast<vtkIdType>(run.NonFinitePoints));
    fd->AddArray(nonFinite);
  }
  if (run.CoincidentPoints > 0)
  {
    vtkNew<vtkIdTypeArray> coincident;
    coincident->SetName(vtkGLSArrayNames::CoincidentPoints);
    coincident->InsertNextValue(static_cast<vtkIdType>(run.CoincidentPoints));
    fd->AddArray(coincident);
  }
  if (!run.EvaluationUsed.empty())
  {
    vtkNew<vtkStringArray> evaluation;
    evaluation->SetName(vtkGLSArrayNames::Evaluation);
    evaluation->InsertNextValue(run.EvaluationUsed);
    fd->AddArray(evaluation);
    if (run.EvaluationUsed == "Multiresolution")
    {
      vtkNew<vtkDoubleArray> accuracy;
      accuracy->SetName(vtkGLSArrayNames::Accuracy);
      accuracy->InsertNextValue(run.AccuracyUsed);
      fd->AddArray(accuracy);
    }
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
  os << indent << "MemoryBudget (MiB): " << this->MemoryBudget << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
}
