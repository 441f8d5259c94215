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
