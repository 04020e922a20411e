// Host/device qualifiers: the one place that knows whether code is being compiled for CUDA.
// Shared per-pixel, per-triangle and per-texel code is written once with DV_HD and compiled
// by g++ for CPU threads and by nvcc for CUDA kernels (see cuda/execute.h).
#pragma once

#if defined(__CUDACC__)
#define DV_HD __host__ __device__
#define DV_DEVICE __device__
#define DV_KERNEL_LAMBDA [=] __host__ __device__
#else
#define DV_HD
#define DV_DEVICE
#define DV_KERNEL_LAMBDA [=]
#endif

// A call kept out of line in CUDA code: a function whose body would otherwise be inlined at
// every call site of a large kernel and spill its registers on every path.
#if defined(__CUDACC__)
#define DV_NOINLINE __noinline__
#else
#define DV_NOINLINE
#endif

#if defined(__CUDA_ARCH__)
#define DV_IN_DEVICE_CODE 1
#else
#define DV_IN_DEVICE_CODE 0
#endif

// True when this build can launch CUDA kernels at all (a GPU may still be absent at run time).
#if defined(DEEPVOX_WITH_CUDA)
inline constexpr bool kBuiltWithCuda = true;
#else
inline constexpr bool kBuiltWithCuda = false;
#endif
