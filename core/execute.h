// One parallel-for, two executors: `parallel_for(backend, name, n, lambda)` runs the lambda on
// CPU threads or as a CUDA kernel. Write kernel bodies as DV_KERNEL_LAMBDA over View<> data.
// A translation unit that launches on CUDA must be compiled by nvcc: list it in
// deepvox_kernel_sources() (cmake/DeepvoxCuda.cmake); elsewhere the CUDA branch throws.
#pragma once

#include <cstdint>
#include <string>

#include "core/error.h"
#include "core/hd.h"
#include "core/parallel.h"

#if defined(__CUDACC__)
#include "cuda/launch.cuh"
#endif

namespace dv {

enum class Backend : uint8_t { cpu, cuda };

const char* to_string(Backend backend);
Backend parse_backend(const std::string& name);  // "cpu" | "cuda"; throws InputError
// CUDA when this build has it and a device is present, else CPU.
Backend default_backend();
// Throws an Error with the reason when `backend` cannot run here.
void require_backend(Backend backend);

template <class F>
void parallel_for(Backend backend, const char* name, int64_t n, F body) {
  if (backend == Backend::cuda) {
#if defined(__CUDACC__)
    cuda_parallel_for(name, n, body);
#else
    throw Error(std::string(name) + ": CUDA launch from a file not compiled by nvcc");
#endif
  } else {
    cpu_parallel_for(n, body);
  }
}

}  // namespace dv
