// One parallel-for, two executors: `parallel_for(backend, name, n, lambda)` runs the lambda on
// CPU threads or as a CUDA kernel. Write kernel bodies as DV_KERNEL_LAMBDA over View<> data.
// A translation unit that calls parallel_for must be compiled by nvcc when the build has CUDA:
// list it in deepvox_kernel_sources() (cmake/DeepvoxCuda.cmake). Forgetting it fails the CUDA
// build at the call (a static_assert), not a run on the GPU machine.
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
                "compiles it (cmake/DeepvoxCuda.cmake)");
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

}  // namespace dv
