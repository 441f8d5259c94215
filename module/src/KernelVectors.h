// Private to the CPU kernels (OnePassKernel.cpp, MultiresolutionKernel.cpp): four-double vectors and the run-time
// choice of an AVX2 + FMA build of a loop.
#pragma once

#include "gls/HostDevice.h"

#include <cstring>

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define GLS_KERNEL_DISPATCH 1
#else
#define GLS_KERNEL_DISPATCH 0
#endif

namespace gls
{
namespace kernel
{

#if defined(__GNUC__)
#define GLS_KERNEL_VECTORS 1
/// Four doubles (GCC/clang vector extension: two SSE2 registers in the baseline build, one AVX register in the
/// AVX2 build). Loaded and stored through memcpy, so no aliasing rule is bent. The helpers are always inlined, so
/// the vector-argument ABI that -Wpsabi warns about never applies.
typedef double Double4 __attribute__((vector_size(32)));

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

GLS_FORCE_INLINE Double4 load4(const double* m)
{
  Double4 v;
  std::memcpy(&v, m, sizeof(v));
  return v;
}

GLS_FORCE_INLINE void store4(double* m, Double4 v)
{
  std::memcpy(m, &v, sizeof(v));
}

/// Adds the `count` values f times 1, d2 and (with `fourth`) d4 to the rows m[0, count), m[stride, stride + count) and
/// m[2 stride, 2 stride + count): four at a time while four remain (formed from the values, `gathered`, when they are
/// held in registers, else loaded with load4), then one by one. The same products and sums as the scalar loop,
/// element by element (fused into multiply-adds in the AVX2 build). Callers pass constants, so the loops unroll.
GLS_FORCE_INLINE void addTimesPowers(
  double* m, const double* f, int count, int stride, bool gathered, double d2, double d4, bool fourth = true)
{
  int j = 0;
  for (; j + 4 <= count; j += 4)
  {
    const Double4 v = gathered ? Double4{ f[j], f[j + 1], f[j + 2], f[j + 3] } : load4(f + j);
    store4(m + j, load4(m + j) + v);
    store4(m + stride + j, load4(m + stride + j) + d2 * v);
    if (fourth)
    {
      store4(m + 2 * stride + j, load4(m + 2 * stride + j) + d4 * v);
    }
  }
  for (; j < count; ++j)
  {
    m[j] += f[j];
    m[stride + j] += d2 * f[j];
    if (fourth)
    {
      m[2 * stride + j] += d4 * f[j];
    }
  }
}

#pragma GCC diagnostic pop
#else
#define GLS_KERNEL_VECTORS 0
#endif

#if GLS_KERNEL_DISPATCH
/// True when the processor has AVX2 and FMA (checked once).
inline bool hasAvx2()
{
  static const bool yes = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return yes;
}
#endif

} // namespace kernel
} // namespace gls
