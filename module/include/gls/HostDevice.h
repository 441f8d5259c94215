// GLS_HOST_DEVICE marks functions compiled for both the CPU and the CUDA device, so that the per-point math is
// written once and the CPU tests also test the arithmetic the GPU runs.
#pragma once

#if defined(__CUDACC__)
#define GLS_HOST_DEVICE __host__ __device__
#else
#define GLS_HOST_DEVICE
#endif

#define GLS_INLINE GLS_HOST_DEVICE inline

/// GLS_FORCE_INLINE (a function) and GLS_INLINE_LAMBDA (a lambda) are inlined into their caller on the host (GCC or
/// clang on x86): a function or lambda left out of line is compiled for the baseline target, so one called from the
/// CPU kernels' AVX2 builds (KernelVectors.h) would run without AVX2 and FMA. For nvcc, GLS_INLINE and nothing.
#if defined(__GNUC__) && !defined(__CUDACC__) && (defined(__x86_64__) || defined(__i386__))
#define GLS_FORCE_INLINE inline __attribute__((always_inline))
#define GLS_INLINE_LAMBDA __attribute__((always_inline))
#else
#define GLS_FORCE_INLINE GLS_INLINE
#define GLS_INLINE_LAMBDA
#endif
