// Coincident points: several input points at exactly the same coordinates (an OBJ reader splitting vertices per
// face corner, merged scans, repeated rows). They would count several times in every neighbourhood (a PCA of the k
// nearest points then sees fewer distinct points than k, and the GLS sums weigh them k times), so the filters merge
// them: each distinct position is computed once, counted once, and its results are written back to every copy.
#pragma once

#include "gls/UninitializedArray.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gls
{

/// Indices of points (UninitializedArray: filled by parallel loops).
using PointIndices = UninitializedArray<std::uint64_t>;

/// Which points share their coordinates with an earlier one. Points with a non-finite coordinate are never merged.
struct CoincidentPoints
{
  PointIndices representative; ///< per point: its distinct position's index in `distinct`
  PointIndices distinct;       ///< per distinct position: its first point (input order)
  /// distinct position u has the points copies[copyStart[u] .. copyStart[u+1])
  PointIndices copyStart;
  PointIndices copies; ///< every point, grouped by distinct position, in input order within a group

  /// Number of points merged into an earlier one (0: every position is distinct).
  std::size_t merged() const { return this->representative.size() - this->distinct.size(); }
};

/// Finds the coincident points among n interleaved xyz triples (bitwise-equal coordinates; -0 and +0 are equal),
/// with up to `threads` threads (0: every hardware thread). Deterministic, the same for any thread count;
/// O(n log n).
CoincidentPoints findCoincidentPoints(const double* xyz, std::size_t n, int threads = 1);

/// Gathers `width` values per point of the distinct positions (the first copy's values) from per-point `values`.
std::vector<double> distinctValues(const CoincidentPoints& c, const double* values, int width);

/// The normal of each distinct position from its copies' (n per point, 3 each): the first copy's when they are all
/// equal, else the normalized sum of the copies' unit normals (zero or non-finite ones left out); (0, 0, 0), which
/// leaves the position out of every fit, when they cancel.
std::vector<double> mergedNormals(const CoincidentPoints& c, const double* normals);

/// Writes per-distinct-position `values` (width each) back to every copy, into `out` (width per input point).
void scatterToCopies(const CoincidentPoints& c, const double* values, int width, double* out);

} // namespace gls
