// The points a GLS filter computes on (private to the module): this piece's points with their normals, then the
// ghosts other ranks sent, and, when some points coincide, their merging (gls/CoincidentPoints.h): each distinct
// position is computed and counted once and its results go back to every copy.
#ifndef vtkGLSCloud_h
#define vtkGLSCloud_h

#include "gls/CoincidentPoints.h"

#include <algorithm>
#include <cstddef>
#include <vector>

struct vtkGLSCloud
{
  /// Points are the input's coordinates less this (the low corner of the finite bounds of the whole input, on every
  /// process), so that every computation sees the same numbers wherever the data sits: a survey at UTM coordinates
  /// and the same points moved to the origin give the same results (their differences are the same doubles). A
  /// filter that writes positions adds it back.
  double Anchor[3] = { 0.0, 0.0, 0.0 };
  std::vector<double> Points;  ///< 3 per point, less Anchor
  std::vector<double> Normals; ///< 3 per point (empty when the filter has none, e.g. normal estimation)
  /// Bytes a point takes in Points and Normals.
  static constexpr double BytesPerPoint = 6 * sizeof(double);
  std::size_t Owned = 0;       ///< this piece's points, the first ones

  /// After MergeCoincident: which input points (owned, then ghosts) share a position. Empty when none was merged.
  gls::CoincidentPoints Copies;
  std::size_t InputOwned = 0; ///< this piece's input points (Owned before the merge)
  std::size_t ReleasedSize = 0; ///< Size() once ReleaseCoordinates freed Points

  std::size_t Size() const { return this->Points.empty() ? this->ReleasedSize : this->Points.size() / 3; }
  /// Frees Points and Normals once a fitting engine holds its own copies of them and nothing reads them any more
  /// (a fit that is not cut into tiles): Size() and Ghosts() still count the points.
  void ReleaseCoordinates()
  {
    this->ReleasedSize = this->Size();
    std::vector<double>().swap(this->Points);
    std::vector<double>().swap(this->Normals);
  }
  std::size_t Ghosts() const { return this->Size() - this->Owned; }
  bool IsMerged() const { return !this->Copies.representative.empty(); }

  /// Merges the points at bitwise-equal coordinates: Points (and Normals, by gls::mergedNormals) become the
  /// distinct positions, this piece's first, and Owned their number. Returns how many of this piece's input
  /// points were merged into an earlier one; nothing changes (and 0 is returned) when every position is distinct.
  /// Uses up to `threads` threads (0: every hardware thread); the result is the same for any count.
  std::size_t MergeCoincident(int threads = 1);

  /// Writes per-position values (width each, `Owned` positions) back to every copy of this piece's input points,
  /// converted to Out (a narrower type rounds them to nearest).
  template <typename In, typename Out>
  void ScatterToInput(const In* values, int width, Out* out) const
  {
    const std::size_t w = static_cast<std::size_t>(width);
    if (!this->IsMerged())
    {
      std::copy(values, values + w * this->Owned, out);
      return;
    }
    for (std::size_t i = 0; i < this->InputOwned; ++i)
    {
      const std::size_t u = this->Copies.representative[i];
      std::copy(values + w * u, values + w * u + w, out + w * i);
    }
  }
};

#endif
