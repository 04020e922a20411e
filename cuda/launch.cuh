// CUDA executor of parallel_for: one generic kernel that calls the lambda per index, with the
// launch checked and named. Only included by nvcc-compiled files (through core/execute.h).
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "core/cuda_check.h"

namespace dv {

template <class F>
__global__ void parallel_for_kernel(int64_t n, F body) {
  int64_t i = int64_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < n) body(i);
}

// Launches asynchronously on the default stream; errors of the launch itself are reported here
// with `name`, errors during execution at the next synchronising call.
template <class F>
void cuda_parallel_for(const char* name, int64_t n, F body, int block_size = 128) {
  if (n <= 0) return;
  int64_t blocks = (n + block_size - 1) / block_size;
  parallel_for_kernel<<<unsigned(blocks), block_size>>>(n, body);
  check_cuda(cudaGetLastError(), name, __FILE__, __LINE__);
}

}  // namespace dv
