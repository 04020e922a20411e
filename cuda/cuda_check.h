// CUDA error checking that names the failing call, file and line (only in CUDA builds).
#pragma once

#include <cuda_runtime_api.h>

#include <string>

#include "core/error.h"

namespace dv {

inline void check_cuda(cudaError_t err, const char* call, const char* file, int line) {
  if (err == cudaSuccess) return;
  cudaGetLastError();  // clear a sticky-free error so later calls can report their own
  throw Error(std::string("CUDA error in ") + call + " at " + file + ":" + std::to_string(line) +
              ": " + cudaGetErrorName(err) + " (" + cudaGetErrorString(err) + ")");
}

}  // namespace dv

#define DV_CUDA_CHECK(call) ::dv::check_cuda((call), #call, __FILE__, __LINE__)
