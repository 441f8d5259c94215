// The moments of the multi-resolution pass (docs/math.md, "Multi-resolution evaluation"): the exact pass's
// A_k = sum d^(2k) f for k = 0, 1, 2, where a sample is either one point or a whole cell of points (CellMoments.h:
// its points weighted by a linear field across the cell and binned by a spread of squared distances). Because
// |x|^2 of a cell's points is no longer its weight's d^2, every fitted value f of the moment set (MomentSet.h) is
// stored.
#pragma once

#include "gls/MomentBins.h"
#include "gls/MomentSet.h"

namespace gls
{

/// m[k * kFitValues + j] = sum over the samples of d^(2k) f_j (k = 0, 1, 2). Padded to whole 64-byte lines.
struct alignas(64) AggregateMoments
{
  double m[wholeCacheLines(3 * kFitValues)];
};

GLS_INLINE void clearMoments(AggregateMoments& a)
{
  for (int i = 0; i < 3 * kFitValues; ++i)
  {
    a.m[i] = 0.0;
  }
}

GLS_INLINE void addMoments(AggregateMoments& a, const AggregateMoments& b)
{
  for (int i = 0; i < 3 * kFitValues; ++i)
  {
    a.m[i] += b.m[i];
  }
}

/// Number of points in the ball the moments describe (cells count all their points).
GLS_INLINE double neighborCount(const AggregateMoments& a)
{
  return a.m[0];
}

/// Adds the values f (MomentSet.h) of a sample whose points all sit at squared distance d2.
GLS_INLINE void addSampleSums(AggregateMoments& a, const double* f, double d2)
{
  const double d4 = d2 * d2;
  for (int j = 0; j < kFitValues; ++j)
  {
    a.m[j] += f[j];
    a.m[kFitValues + j] += d2 * f[j];
    a.m[2 * kFitValues + j] += d4 * f[j];
  }
}

/// Adds one point with local position x (d2 = |x|^2) and normal n: exactly what the exact pass adds.
GLS_INLINE void addPoint(AggregateMoments& a, const Vec3& x, double d2, const Vec3& n)
{
  double f[kFitValues];
  pointValues(x, d2, n, f);
  addSampleSums(a, f, d2);
}

/// Weighted sums at scale t (s) and their t-derivatives (ds) from the moments of the ball of radius t.
GLS_INLINE void weightedSumsFromMoments(const AggregateMoments& a, double t, WeightedSums& s, WeightedSums& ds)
{
  const WeightPolynomial w = weightPolynomial(t);
  double v[kFitValues];
  double dv[kFitValues];
  for (int j = 0; j < kFitValues; ++j)
  {
    const double a0 = a.m[j], a1 = a.m[kFitValues + j], a2 = a.m[2 * kFitValues + j];
    v[j] = a0 + w.c1 * a1 + w.c2 * a2;
    dv[j] = w.e1 * a1 + w.e2 * a2;
  }
  toWeightedSums(v, dv, s, ds);
}

} // namespace gls
