// CUDA executor of parallel_for: one generic kernel that calls the lambda per index, launched
// with the block size the occupancy calculator picks for that lambda (cached per kernel), the
// launch checked and named, and timed per kernel name when kernel timing is on
// (cuda/kernel_timing.h). Only included by nvcc-compiled files (through cuda/execute.h).
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "cuda/cuda_check.h"
#include "cuda/kernel_timing.h"

namespace dv {

template <class F>
__global__ void parallel_for_kernel(int64_t n, F body) {
  int64_t i = int64_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < n) body(i);
}

// The block size that gives this kernel the highest occupancy (registers and shared memory of
// its own body), asked once per kernel; 128 if the calculator cannot answer.
template <class F>
int occupancy_block_size() {
  static const int block_size = [] {
    int min_grid = 0;
    int block = 0;
    if (cudaOccupancyMaxPotentialBlockSize(&min_grid, &block, parallel_for_kernel<F>) !=
            cudaSuccess ||
        block <= 0) {
      cudaGetLastError();
      return 128;
    }
    return block;
  }();
  return block_size;
}

// Launches asynchronously on the default stream; errors of the launch itself are reported here
// with `name`, errors during execution at the next synchronising call. With kernel timing on,
// the launch is bracketed by events and waited for (timing runs are for profiling).
template <class F>
void cuda_parallel_for(const char* name, int64_t n, F body) {
  if (n <= 0) return;
  const int block_size = occupancy_block_size<F>();
  const int64_t blocks = (n + block_size - 1) / block_size;
  KernelTimingScope timing(name, block_size);
  parallel_for_kernel<<<unsigned(blocks), block_size>>>(n, body);
  check_cuda(cudaGetLastError(), name, __FILE__, __LINE__);
  timing.finish();
}

}  // namespace dv
