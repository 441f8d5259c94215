// GLS_HOST_DEVICE marks functions compiled for both the CPU and the CUDA device, so that the per-point math is
// written once and the CPU tests also test the arithmetic the GPU runs.
#pragma once

#if defined(__CUDACC__)
#define GLS_HOST_DEVICE __host__ __device__
#else
#define GLS_HOST_DEVICE
#endif

#define GLS_INLINE GLS_HOST_DEVICE inline
