// CUDA executor of parallel_for: one generic kernel that calls the lambda per index, launched
// with the block size the occupancy calculator picks for that lambda (cached per kernel), the
// launch checked and named, and timed per kernel name when kernel timing is on
// (cuda/kernel_timing.h). Only included by nvcc-compiled files (through cuda/execute.h).
#pragma once

#include <cuda_runtime.h>

#include <algorithm>
#include <cstdint>
#include <string>

#include "core/error.h"
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

// The SMs of the current device, asked once (1 if the runtime cannot answer).
inline int cuda_multiprocessors() {
  static const int count = [] {
    int device = 0, value = 0;
    if (cudaGetDevice(&device) != cudaSuccess ||
        cudaDeviceGetAttribute(&value, cudaDevAttrMultiProcessorCount, device) != cudaSuccess ||
        value <= 0) {
      cudaGetLastError();
      return 1;
    }
    return value;
  }();
  return count;
}

// The block size of an n-thread launch: the occupancy one, shrunk in steps of a warp (to no
// less than 64 threads) while the launch would give an SM fewer than four blocks, so that a
// small launch whose threads do uneven work (one thread per triangle) still reaches every SM.
inline int spread_block_size(int64_t n, int occupancy_block) {
  const int64_t wanted_blocks = 4 * int64_t(cuda_multiprocessors());
  if (n >= wanted_blocks * occupancy_block) return occupancy_block;
  const int64_t per_block = ((n + wanted_blocks - 1) / wanted_blocks + 31) / 32 * 32;
  return int(std::clamp<int64_t>(per_block, std::min(64, occupancy_block), occupancy_block));
}

// Launches asynchronously on the default stream; errors of the launch itself are reported here
// with `name`, errors during execution at the next synchronising call. With kernel timing on,
// the launch is bracketed by events and waited for (timing runs are for profiling).
template <class F>
void cuda_parallel_for(const char* name, int64_t n, F body) {
  if (n <= 0) return;
  const int block_size = spread_block_size(n, occupancy_block_size<F>());
  const int64_t blocks = (n + block_size - 1) / block_size;
  if (blocks > int64_t(INT32_MAX))  // the grid's x limit: past it the launch would fail or wrap
    throw Error(std::string(name) + ": " + std::to_string(n) +
                " threads need more blocks than one launch can hold (2^31 - 1)");
  KernelTimingScope timing(name, block_size);
  parallel_for_kernel<<<unsigned(blocks), block_size>>>(n, body);
  check_cuda(cudaGetLastError(), name, __FILE__, __LINE__);
  timing.finish();
}

// parallel_for_kernel with a register budget: __launch_bounds__(kBoundedBlock, kMinBlocks) lets
// at most 65536 / (kMinBlocks * kBoundedBlock) registers per thread, so that kMinBlocks blocks fit
// an SM (the compiler spills what does not fit). For heavy kernels whose warps wait on
// dependent arithmetic, more resident warps can hide more of that latency than the spills cost.
inline constexpr int kBoundedBlock = 256;

template <int kMinBlocks, class F>
__global__ void __launch_bounds__(kBoundedBlock, kMinBlocks)
    bounded_parallel_for_kernel(int64_t n, F body) {
  int64_t i = int64_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < n) body(i);
}

template <int kMinBlocks, class F>
void cuda_bounded_parallel_for(const char* name, int64_t n, F body) {
  if (n <= 0) return;
  const int block_size = spread_block_size(n, kBoundedBlock);
  const int64_t blocks = (n + block_size - 1) / block_size;
  if (blocks > int64_t(INT32_MAX))
    throw Error(std::string(name) + ": " + std::to_string(n) +
                " threads need more blocks than one launch can hold (2^31 - 1)");
  KernelTimingScope timing(name, block_size);
  bounded_parallel_for_kernel<kMinBlocks><<<unsigned(blocks), block_size>>>(n, body);
  check_cuda(cudaGetLastError(), name, __FILE__, __LINE__);
  timing.finish();
}

// Threads of one full wave of parallel_for_kernel<F>: every SM holding as many of its blocks
// as its registers allow (asked once per kernel).
template <class F>
int64_t cuda_resident_threads() {
  const int block_size = occupancy_block_size<F>();
  static const int blocks_per_sm = [block_size] {
    int blocks = 0;
    if (cudaOccupancyMaxActiveBlocksPerMultiprocessor(&blocks, parallel_for_kernel<F>, block_size,
                                                      0) != cudaSuccess ||
        blocks <= 0) {
      cudaGetLastError();
      return 1;
    }
    return blocks;
  }();
  return int64_t(blocks_per_sm) * cuda_multiprocessors() * block_size;
}

}  // namespace dv
