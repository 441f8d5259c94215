#include "vtkGLSDistributedCloud.h"

#include "gls/PointBox.h"
#include "gls/StrayPoints.h"


#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkMultiProcessController.h"
#include "vtkPointData.h"
#include "vtkDataSet.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace
{
constexpr int kGhostCountTag = 48211;
constexpr int kGhostRowsTag = 48212;

bool finite3(const double* p)
{
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

/// Squared distance from p to the box [lo, hi] (0 inside).
double distance2ToBox(const double* p, const double* lo, const double* hi)
{
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const double d = p[a] < lo[a] ? lo[a] - p[a] : (p[a] > hi[a] ? p[a] - hi[a] : 0.0);
    d2 += d * d;
  }
  return d2;
}

bool ghostsDisabled()
{
  const char* v = std::getenv("GLS_DISTRIBUTED_NO_GHOSTS");
  return v && std::strcmp(v, "1") == 0;
}

/// This piece's box of finite points and the reach it needs: lo (3), hi (3), reach. An empty piece has lo > hi: it
/// needs nothing.
std::array<double, 7> boxAndReach(const double* rows, std::size_t n, int width, double reach)
{
  const double inf = std::numeric_limits<double>::infinity();
  std::array<double, 7> box = { inf, inf, inf, -inf, -inf, -inf, reach };
  for (std::size_t i = 0; i < n; ++i)
  {
    const double* p = rows + static_cast<std::size_t>(width) * i;
    if (!finite3(p))
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      box[a] = std::min(box[a], p[a]);
      box[3 + a] = std::max(box[3 + a], p[a]);
    }
  }
  return box;
}

/// The rows (finite ones) within a partner's reach of its box (boxAndReach's 7 values); none for a partner without
/// points or reach.
std::vector<double> rowsNear(const double* rows, std::size_t n, int width, const double* box)
{
  std::vector<double> out;
  if (!(box[0] <= box[3]) || !(box[6] >= 0.0))
  {
    return out;
  }
  const double r2 = box[6] * box[6];
  for (std::size_t i = 0; i < n; ++i)
  {
    const double* p = rows + static_cast<std::size_t>(width) * i;
    if (finite3(p) && distance2ToBox(p, box, box + 3) <= r2)
    {
      out.insert(out.end(), p, p + width);
    }
  }
  return out;
}

/// Per-rank lengths (in doubles) and offsets of `counts` rows of `width` doubles laid end to end; returns the total.
vtkIdType rowBlocks(const std::vector<long long>& counts, int width, std::vector<vtkIdType>& lengths,
  std::vector<vtkIdType>& offsets)
{
  lengths.resize(counts.size());
  offsets.resize(counts.size());
  vtkIdType total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r)
  {
    lengths[r] = static_cast<vtkIdType>(counts[r]) * width;
    offsets[r] = total;
    total += lengths[r];
  }
  return total;
}
}

vtkGLSDistributedCloud::vtkGLSDistributedCloud(vtkMultiProcessController* controller)
{
  if (controller && controller->GetNumberOfProcesses() > 1)
  {
    this->Controller = controller;
    this->Rank = controller->GetLocalProcessId();
    this->Size = controller->GetNumberOfProcesses();
  }
}

bool vtkGLSDistributedCloud::AllTrue(bool local) const
{
  if (!this->Controller)
  {
    return local;
  }
  return this->Min(local ? 1.0 : 0.0) > 0.5;
}

double vtkGLSDistributedCloud::Sum(double local) const
{
  double global = local;
  if (this->Controller)
  {
    this->Controller->AllReduce(&local, &global, 1, vtkCommunicator::SUM_OP);
  }
  return global;
}

double vtkGLSDistributedCloud::Min(double local) const
{
  double global = local;
  if (this->Controller)
  {
    this->Controller->AllReduce(&local, &global, 1, vtkCommunicator::MIN_OP);
  }
  return global;
}

double vtkGLSDistributedCloud::Max(double local) const
{
  double global = local;
  if (this->Controller)
  {
    this->Controller->AllReduce(&local, &global, 1, vtkCommunicator::MAX_OP);
  }
  return global;
}

bool vtkGLSDistributedCloud::FiniteBounds(const double* xyz, std::size_t n, double bounds[6]) const
{
  const double inf = std::numeric_limits<double>::infinity();
  const gls::PointBox box = gls::boxOfFinitePoints(xyz, n);
  double lo[3] = { inf, inf, inf }, negHi[3] = { inf, inf, inf };
  for (int a = 0; a < 3 && box.count > 0; ++a)
  {
    lo[a] = box.low[a];
    negHi[a] = -box.high[a];
  }
  double local[6] = { lo[0], lo[1], lo[2], negHi[0], negHi[1], negHi[2] }, global[6];
  std::copy(local, local + 6, global);
  if (this->Controller)
  {
    this->Controller->AllReduce(local, global, 6, vtkCommunicator::MIN_OP);
  }
  if (!(global[0] < inf))
  {
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = global[a];
    bounds[2 * a + 1] = -global[3 + a];
  }
  return true;
}

bool vtkGLSDistributedCloud::ExchangeGhosts(const double* rows, std::size_t n, int width, double reach,
  std::vector<double>& ghosts, std::size_t& ghostCount) const
{
  ghostCount = 0;
  if (!this->Controller)
  {
    return true;
  }
  // Every rank's box of finite points and the reach it needs.
  const std::array<double, 7> mine = boxAndReach(rows, n, width, reach);
  std::vector<double> boxes(7 * static_cast<std::size_t>(this->Size));
  if (!this->Controller->AllGather(mine.data(), boxes.data(), 7))
  {
    return false;
  }
  const bool disabled = ghostsDisabled();
  // Round-robin pairing (circle method): in round r, rank i talks to (r - i) mod P; every pair meets once.
  const int P = this->Size % 2 == 0 ? this->Size : this->Size + 1;
  std::vector<std::vector<double>> received(static_cast<std::size_t>(this->Size));
  for (int round = 0; round < P; ++round)
  {
    const int partner = ((round - this->Rank) % P + P) % P;
    if (partner == this->Rank || partner >= this->Size)
    {
      continue;
    }
    // What the partner needs from us.
    const std::vector<double> out =
      disabled ? std::vector<double>() : rowsNear(rows, n, width, &boxes[7 * static_cast<std::size_t>(partner)]);
    if (!this->SwapRows(partner, out, received[static_cast<std::size_t>(partner)]))
    {
      return false;
    }
  }
  for (const std::vector<double>& block : received)
  {
    ghosts.insert(ghosts.end(), block.begin(), block.end());
    ghostCount += block.size() / static_cast<std::size_t>(width);
  }
  return true;
}

bool vtkGLSDistributedCloud::SwapRows(int partner, const std::vector<double>& out, std::vector<double>& in) const
{
  const auto sendOut = [&]() {
    vtkIdType count = static_cast<vtkIdType>(out.size());
    return this->Controller->Send(&count, 1, partner, kGhostCountTag) &&
      (count == 0 || this->Controller->Send(out.data(), count, partner, kGhostRowsTag));
  };
  const auto receiveIn = [&]() {
    vtkIdType count = 0;
    if (!this->Controller->Receive(&count, 1, partner, kGhostCountTag))
    {
      return false;
    }
    in.resize(static_cast<std::size_t>(count));
    return count == 0 || this->Controller->Receive(in.data(), count, partner, kGhostRowsTag);
  };
  // The lower rank of a pair sends first, so blocking sends and receives never wait on each other in a cycle.
  return this->Rank < partner ? (sendOut() && receiveIn()) : (receiveIn() && sendOut());
}

bool vtkGLSDistributedCloud::AppendGhosts(std::vector<double>& points, std::size_t owned,
  std::initializer_list<Column> columns, double reach, std::size_t& ghostCount) const
{
  ghostCount = 0;
  if (!this->Controller)
  {
    return true;
  }
  int width = 3;
  for (const Column& c : columns)
  {
    width += c.Width;
  }
  const std::size_t w = static_cast<std::size_t>(width);
  std::vector<double> rows(w * owned);
  for (std::size_t i = 0; i < owned; ++i)
  {
    double* row = &rows[w * i];
    std::copy(&points[3 * i], &points[3 * i] + 3, row);
    row += 3;
    for (const Column& c : columns)
    {
      const std::size_t cw = static_cast<std::size_t>(c.Width);
      std::copy(&(*c.Values)[cw * i], &(*c.Values)[cw * i] + cw, row);
      row += cw;
    }
  }
  std::vector<double> ghosts;
  if (!this->ExchangeGhosts(rows.data(), owned, width, reach, ghosts, ghostCount))
  {
    return false;
  }
  points.reserve(3 * (owned + ghostCount));
  for (std::size_t g = 0; g < ghostCount; ++g)
  {
    const double* row = &ghosts[w * g];
    points.insert(points.end(), row, row + 3);
    row += 3;
    for (const Column& c : columns)
    {
      c.Values->insert(c.Values->end(), row, row + c.Width);
      row += c.Width;
    }
  }
  return true;
}

bool vtkGLSDistributedCloud::AllInOnePlaneZ(bool planar, bool any, double z) const
{
  if (!this->Controller)
  {
    return planar;
  }
  const double inf = std::numeric_limits<double>::infinity();
  const bool allPlanar = this->AllTrue(planar || !any);
  const bool anywhere = this->Max(any ? 1.0 : 0.0) > 0.5;
  const double zmin = this->Min(any ? z : inf), zmax = this->Max(any ? z : -inf);
  return allPlanar && anywhere && zmin == zmax;
}

std::vector<long long> vtkGLSDistributedCloud::GlobalIds(vtkDataSet* piece) const
{
  const vtkIdType n = piece ? piece->GetNumberOfPoints() : 0;
  std::vector<long long> ids(static_cast<std::size_t>(n));
  long long offset = 0;
  if (!this->RankOrderIds(piece, offset))
  {
    vtkDataArray* given = n > 0 ? piece->GetPointData()->GetGlobalIds() : nullptr; // every piece with points has it
    for (vtkIdType i = 0; i < n; ++i)
    {
      ids[static_cast<std::size_t>(i)] = static_cast<long long>(given->GetComponent(i, 0));
    }
    return ids;
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    ids[static_cast<std::size_t>(i)] = offset + i;
  }
  return ids;
}

bool vtkGLSDistributedCloud::RankOrderIds(vtkDataSet* piece, long long& offset) const
{
  const vtkIdType n = piece ? piece->GetNumberOfPoints() : 0;
  vtkDataArray* given = piece ? piece->GetPointData()->GetGlobalIds() : nullptr;
  const bool haveGiven = given && given->GetNumberOfComponents() == 1 && given->GetNumberOfTuples() == n;
  offset = 0;
  if (this->AllTrue(haveGiven || n == 0) && this->Max(haveGiven ? 1.0 : 0.0) > 0.5)
  {
    return false;
  }
  if (this->Controller)
  {
    std::vector<long long> counts(static_cast<std::size_t>(this->Size));
    const long long mine = n;
    this->Controller->AllGather(&mine, counts.data(), 1);
    for (int r = 0; r < this->Rank; ++r)
    {
      offset += counts[static_cast<std::size_t>(r)];
    }
  }
  return true;
}

bool vtkGLSDistributedCloud::GatherRows(const std::vector<double>& local, int width, int root,
  std::vector<double>& all, std::vector<long long>& counts) const
{
  const long long mine = static_cast<long long>(local.size() / static_cast<std::size_t>(width));
  counts.assign(static_cast<std::size_t>(this->Size), mine);
  if (!this->Controller)
  {
    all = local;
    return true;
  }
  if (!this->Controller->AllGather(&mine, counts.data(), 1))
  {
    return false;
  }
  std::vector<vtkIdType> lengths, offsets;
  const vtkIdType total = rowBlocks(counts, width, lengths, offsets);
  all.assign(this->Rank == root ? static_cast<std::size_t>(total) : 0, 0.0);
  return this->Controller->GatherV(local.data(), all.data(), static_cast<vtkIdType>(local.size()),
           lengths.data(), offsets.data(), root) != 0;
}

bool vtkGLSDistributedCloud::ScatterRows(const std::vector<double>& all, int width, int root,
  const std::vector<long long>& counts, std::vector<double>& local) const
{
  if (!this->Controller)
  {
    local = all;
    return true;
  }
  std::vector<vtkIdType> lengths, offsets;
  rowBlocks(counts, width, lengths, offsets);
  local.assign(static_cast<std::size_t>(lengths[static_cast<std::size_t>(this->Rank)]), 0.0);
  return this->Controller->ScatterV(all.data(), local.data(), lengths.data(), offsets.data(),
           lengths[static_cast<std::size_t>(this->Rank)], root) != 0;
}

bool vtkGLSDistributedCloud::StrayPoints(const double* xyz, std::size_t n, std::vector<std::uint64_t>& stray) const
{
  stray.clear();
  if (!this->Controller)
  {
    stray = gls::findStrayPoints(xyz, n);
    return true;
  }
  std::size_t finite = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    finite += finite3(xyz + 3 * i) ? 1 : 0;
  }
  const double total = this->Sum(static_cast<double>(n));
  const double allFinite = this->Sum(static_cast<double>(finite));
  // The robust box from every rank's sample, worked out on rank 0 and sent to every rank (low, high, extent, valid).
  std::vector<double> sample, samples, box;
  std::vector<long long> counts;
  gls::appendStraySample(xyz, n, gls::straySampleStride(static_cast<std::size_t>(total)), sample);
  if (!this->GatherRows(sample, 3, 0, samples, counts))
  {
    return false;
  }
  std::vector<double> boxes;
  if (this->Rank == 0)
  {
    const gls::StrayBox b = gls::strayBoxOfSample(samples, static_cast<std::size_t>(allFinite));
    for (int r = 0; r < this->Size; ++r)
    {
      boxes.insert(boxes.end(), { b.low[0], b.low[1], b.low[2], b.high[0], b.high[1], b.high[2], b.extent,
                                  b.valid ? 1.0 : 0.0 });
    }
  }
  if (!this->ScatterRows(boxes, 8, 0, std::vector<long long>(static_cast<std::size_t>(this->Size), 1), box))
  {
    return false;
  }
  gls::StrayBox b;
  std::copy(box.begin(), box.begin() + 3, b.low);
  std::copy(box.begin() + 3, box.begin() + 6, b.high);
  b.extent = box[6];
  b.valid = box[7] != 0.0;
  // Every rank's candidates on rank 0, which sends each rank the verdicts on its own.
  const std::vector<std::uint64_t> candidates = gls::strayCandidates(xyz, n, b);
  std::vector<double> where, everywhere, verdicts, mine;
  for (std::uint64_t i : candidates)
  {
    where.insert(where.end(), xyz + 3 * i, xyz + 3 * i + 3);
  }
  if (!this->GatherRows(where, 3, 0, everywhere, counts))
  {
    return false;
  }
  if (this->Rank == 0)
  {
    for (unsigned char isolated : gls::isolatedCandidates(everywhere, b))
    {
      verdicts.push_back(isolated);
    }
  }
  if (!this->ScatterRows(verdicts, 1, 0, counts, mine))
  {
    return false;
  }
  for (std::size_t c = 0; c < candidates.size(); ++c)
  {
    if (mine[c] != 0.0)
    {
      stray.push_back(candidates[c]);
    }
  }
  return true;
}
