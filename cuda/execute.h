// One parallel-for, two executors: `parallel_for(backend, name, n, lambda)` runs the lambda on
// CPU threads or as a CUDA kernel. Write kernel bodies as DV_KERNEL_LAMBDA over View<> data.
// A translation unit that calls parallel_for must be compiled by nvcc when the build has CUDA:
// list it in deepvox_kernel_sources() (scripts/cmake/DeepvoxCuda.cmake). Forgetting it fails the
// CUDA build at the call (a static_assert), not a run on the GPU machine.
#pragma once

#include <cstdint>
#include <string>

#include "core/backend.h"
#include "core/error.h"
#include "core/hd.h"
#include "core/parallel.h"

#if defined(__CUDACC__)
#include "cuda/launch.cuh"
#endif

namespace dv {

// CUDA when this build has it and a device is present, else CPU.
Backend default_backend();
// Throws an Error with the reason when `backend` cannot run here.
void require_backend(Backend backend);

// False for every F: a static_assert that fires only where the template is instantiated.
template <class F>
inline constexpr bool kNeverTrue = false;

template <class F>
void parallel_for(Backend backend, const char* name, int64_t n, F body) {
#if defined(DEEPVOX_WITH_CUDA) && !defined(__CUDACC__)
  static_assert(kNeverTrue<F>,
                "this file launches parallel_for: list it in deepvox_kernel_sources() so nvcc "
                "compiles it (scripts/cmake/DeepvoxCuda.cmake)");
#endif
  if (backend == Backend::cuda) {
#if defined(__CUDACC__)
    cuda_parallel_for(name, n, body);
#else
    throw Error(std::string(name) + ": CUDA launch in a build without CUDA");
#endif
  } else {
    cpu_parallel_for(n, body);
  }
}

// body(i, threads): the call of a persistent-thread pass (parallel_for_resident).
template <class F>
struct ResidentBody {
  F body;
  int64_t threads;
  DV_HD void operator()(int64_t i) const { body(i, threads); }
};

// A pass of persistent threads that loop over work whose amount only the device knows: body(i,
// threads) for i in [0, threads), where threads is as many as run at once (CUDA: one full wave
// of the kernel; CPU: 64 per worker thread). More threads than a wave would wait for a second
// one and, each with as much to do, double the pass.
template <class F>
void parallel_for_resident(Backend backend, const char* name, F body) {
  int64_t threads = int64_t(cpu_thread_count()) * 64;
#if defined(__CUDACC__)
  if (backend == Backend::cuda) threads = cuda_resident_threads<ResidentBody<F>>();
#endif
  parallel_for(backend, name, threads, ResidentBody<F>{body, threads});
}

// parallel_for whose CUDA kernel is compiled to fit kMinBlocks blocks of 256 threads on an SM
// (cuda/launch.cuh, bounded_parallel_for_kernel); 1 is parallel_for itself, whose block size the
// occupancy calculator picks. Which budget is faster is a measurement per kernel.
template <int kMinBlocks, class F>
void parallel_for_bounded(Backend backend, const char* name, int64_t n, F body) {
  static_assert(kMinBlocks >= 1, "at least one block per SM");
  if constexpr (kMinBlocks == 1) {
    parallel_for(backend, name, n, body);
  } else {
#if defined(DEEPVOX_WITH_CUDA) && !defined(__CUDACC__)
    static_assert(kNeverTrue<F>,
                  "this file launches parallel_for_bounded: list it in deepvox_kernel_sources() so "
                  "nvcc compiles it (scripts/cmake/DeepvoxCuda.cmake)");
#endif
    if (backend == Backend::cuda) {
#if defined(__CUDACC__)
      cuda_bounded_parallel_for<kMinBlocks>(name, n, body);
#else
      throw Error(std::string(name) + ": CUDA launch in a build without CUDA");
#endif
    } else {
      cpu_parallel_for(n, body);
    }
  }
}

}  // namespace dv
