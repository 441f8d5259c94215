/**
 * @class   vtkGLSDistributedCloud
 * @brief   The collective steps the GLS filters take when a point cloud is split into pieces over several processes.
 *
 * Under `mpirun -np N pvbatch` or a pvserver with N ranks, every rank holds a piece of the cloud (its *owned*
 * points) and runs the same filter. A GLS fit at a point needs the points within the largest scale around it, so a
 * rank needs the other ranks' points near its piece: its *ghosts*. This class does that exchange, and the few
 * reductions that make a distributed run equal a serial one, through a vtkMultiProcessController (ParaView's own
 * MPI controller in pvbatch/pvserver):
 * - AppendGhosts: every rank announces the bounding box of its finite points and the reach it needs around it;
 *   every rank then sends each other rank its points (rows of doubles, coordinates first, then e.g. normals) that
 *   lie within that rank's reach of its box. Pairwise blocking messages in a round-robin schedule (no deadlock, no
 *   MPI-specific calls). A rank receives whole rows; it computes only for its owned points and drops the ghosts.
 * - reductions (AllTrue, Sum, Min, Max, the global finite bounds) so that parameters derived from the data (scales
 *   relative to the bounding-box diagonal, the automatic minimum neighbour count) are the same on every rank;
 * - global point ids: the point-data GlobalIds attribute when present, else the rank-order numbering (the points
 *   of rank 0, then those of rank 1, ...), which is the serial order when the pieces were cut in order;
 * - GatherRows / ScatterRows to a root rank for the steps that are global by nature (minimum-spanning-tree
 *   orientation).
 *
 * With no controller, or one with a single process, every method is the serial identity (no communication), so
 * serial results are unchanged. Every method is collective when parallel: all ranks must call the same methods in
 * the same order, whatever their local data (an empty piece included); a filter decides locally whether it can go
 * on and then calls AllTrue before the next collective step, so that an error on one rank stops every rank instead
 * of hanging them.
 *
 * Testing switch: the environment variable GLS_DISTRIBUTED_NO_GHOSTS=1 makes AppendGhosts send nothing (each
 * rank then computes on its piece alone, which must differ from the serial run near piece boundaries; the MPI
 * tests use it to show that they can fail).
 */
#ifndef vtkGLSDistributedCloud_h
#define vtkGLSDistributedCloud_h

#include "vtkType.h"

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <vector>

class vtkMultiProcessController;
class vtkDataSet;

class vtkGLSDistributedCloud
{
public:
  /// `controller`: the filter's controller; null or a single process means a serial run.
  explicit vtkGLSDistributedCloud(vtkMultiProcessController* controller);

  /// True when more than one process takes part (the collective methods then communicate).
  bool IsParallel() const { return this->Controller != nullptr; }
  int GetRank() const { return this->Rank; }
  int GetSize() const { return this->Size; }

  /// Logical AND of `local` over the ranks.
  bool AllTrue(bool local) const;
  /// Sum, minimum, maximum of one value over the ranks.
  double Sum(double local) const;
  double Min(double local) const;
  double Max(double local) const;

  /// Bounds (xmin, xmax, ymin, ymax, zmin, zmax) of the finite points of every rank's piece (`xyz`: n interleaved
  /// triples). False when no rank has a finite point (bounds untouched).
  bool FiniteBounds(const double* xyz, std::size_t n, double bounds[6]) const;

  /// One attribute column of a piece's points for AppendGhosts: `Width` values per point.
  struct Column
  {
    std::vector<double>* Values;
    int Width;
  };

  /// Appends the ghosts of a piece: the other ranks' points within `reach` (a length >= 0, or infinity for
  /// everything) of this piece's box of finite points, in rank order, to `points` (3 per point, the first `owned`
  /// of them this rank's) and their attribute values to each column (which hold `owned` points' values on entry).
  /// `ghostCount` receives how many were appended. Collective; a serial run appends nothing. False on a
  /// communication error.
  bool AppendGhosts(std::vector<double>& points, std::size_t owned, std::initializer_list<Column> columns,
    double reach, std::size_t& ghostCount) const;

  /// Whether the points of all the pieces lie in one plane z = const, from each rank's verdict on its own (see
  /// gls::PlaneZ): `any` point counts, they are `planar` in the plane z = `z`. False when no point counts
  /// anywhere. The serial identity is `planar`.
  bool AllInOnePlaneZ(bool planar, bool any, double z) const;

  /// The global id of every point of `piece`: its point-data GlobalIds attribute when present (on every rank),
  /// else the rank-order numbering (offset of this rank = number of points of the ranks before it).
  std::vector<long long> GlobalIds(vtkDataSet* piece) const;

  /// True (on every rank) when the pieces carry no GlobalIds attribute, so that GlobalIds numbers them in rank
  /// order: point i of this piece has the id `offset` + i. A caller that only needs some ids need not list all.
  bool RankOrderIds(vtkDataSet* piece, long long& offset) const;

  /// The stray points of this rank's n positions (xyz, 3 each), judged over the whole cloud by the steps of
  /// gls::findStrayPoints: the robust box of every rank's sample (each rank samples every stride-th of its finite
  /// points, the stride of the whole cloud's count), then the candidates of every rank, gathered on rank 0, which
  /// tells each rank which of its own are isolated. Where the whole cloud has at most 2^20 points the sample is every
  /// point: the same stray points as a serial run's. Indices increasing; false on a communication error. The serial
  /// identity is gls::findStrayPoints.
  bool StrayPoints(const double* xyz, std::size_t n, std::vector<std::uint64_t>& stray) const;

  /// Gathers rows of `width` doubles from every rank onto `root` (in rank order); `counts` receives every rank's
  /// number of rows (on every rank). `all` is filled on the root only.
  bool GatherRows(const std::vector<double>& local, int width, int root, std::vector<double>& all,
    std::vector<long long>& counts) const;

  /// The reverse of GatherRows: the root sends every rank its block of `all` (rank order, `counts` rows each);
  /// `local` receives this rank's rows.
  bool ScatterRows(const std::vector<double>& all, int width, int root, const std::vector<long long>& counts,
    std::vector<double>& local) const;

private:
  /// Exchanges ghost rows: `rows` holds n rows of `width` doubles (x, y, z first) of this rank's points; `reach`
  /// (a length >= 0, or infinity for everything) is how far around its own box this rank needs the other ranks'
  /// points. Appends to `ghosts` the rows the other ranks sent (in rank order) and returns their number in
  /// `ghostCount`. Rows with non-finite coordinates are never sent. False on a communication error.
  bool ExchangeGhosts(const double* rows, std::size_t n, int width, double reach, std::vector<double>& ghosts,
    std::size_t& ghostCount) const;
  /// Sends `out` to `partner` and receives its rows into `in` (the lower rank sends first). False on a communication
  /// error.
  bool SwapRows(int partner, const std::vector<double>& out, std::vector<double>& in) const;

  vtkMultiProcessController* Controller = nullptr;
  int Rank = 0;
  int Size = 1;
};

#endif
