#include "vtkGLSCloud.h"

#include <algorithm>

std::size_t vtkGLSCloud::MergeCoincident(int threads)
{
  this->InputOwned = this->Owned;
  gls::CoincidentPoints copies = gls::findCoincidentPoints(this->Points.data(), this->Size(), threads);
  if (copies.merged() == 0)
  {
    return 0;
  }
  // Owned points come first, so the positions first seen among them are the first distinct ones.
  std::size_t owned = 0;
  while (owned < copies.distinct.size() && copies.distinct[owned] < this->Owned)
  {
    ++owned;
  }
  const std::size_t mergedOwned = this->Owned - owned;
  if (!this->Normals.empty())
  {
    this->Normals = gls::mergedNormals(copies, this->Normals.data());
  }
  this->Points = gls::distinctValues(copies, this->Points.data(), 3);
  this->Owned = owned;
  this->Copies = std::move(copies);
  return mergedOwned;
}

