// CUDA executor of parallel_for_with_tables (cuda/execute_with_tables.h): the bounded kernel of
// cuda/launch.cuh whose blocks first copy read-only tables into their shared memory. Only
// included by nvcc-compiled files.
#pragma once

#include <cuda_runtime.h>

#include <algorithm>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "cuda/cuda_check.h"
#include "cuda/kernel_timing.h"
#include "cuda/launch.cuh"
#include "cuda/shared_tables.h"

namespace dv {

// bounded_parallel_for_kernel whose blocks first copy the placed tables into their shared memory
// (cuda/shared_tables.h); body(i, copy) reads them through placed_view.
template <int kMinBlocks, class F>
__global__ void __launch_bounds__(kBoundedBlock, kMinBlocks)
    tables_parallel_for_kernel(int64_t n, SharedTables tables, F body) {
  extern __shared__ __align__(16) unsigned char shared_tables[];
  tables.copy_into(shared_tables, int(threadIdx.x), int(blockDim.x));
  __syncthreads();
  int64_t i = int64_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < n) body(i, static_cast<const unsigned char*>(shared_tables));
}

// Shared memory a block of a kernel at kMinBlocks blocks per SM may give to tables: its share of
// the SM's, less the runtime's reserve per block, and no more than kMaxSharedTableBytes, so that
// the rest of the SM's unified L1 / shared memory stays cache for the kernel's other reads.
inline constexpr int64_t kMaxSharedTableBytes = 64 * 1024;
inline int64_t cuda_shared_table_budget(int min_blocks) {
  static const int64_t per_sm = [] {
    int device = 0, value = 0;
    if (cudaGetDevice(&device) != cudaSuccess ||
        cudaDeviceGetAttribute(&value, cudaDevAttrMaxSharedMemoryPerMultiprocessor, device) !=
            cudaSuccess) {
      cudaGetLastError();
      return int64_t(0);
    }
    return int64_t(value);
  }();
  return std::clamp<int64_t>(per_sm / std::max(min_blocks, 1) - 1024, 0, kMaxSharedTableBytes);
}

// Launches with the tables as placed (SharedTables::place, at most kMaxSharedTableBytes): a
// block's dynamic shared memory past 48 KB needs the kernel's consent, asked once per kernel; a
// refusal is an Error that names the pass and the bytes.
template <int kMinBlocks, class F>
void cuda_tables_parallel_for(const char* name, int64_t n, const SharedTables& tables, F body) {
  if (n <= 0) return;
  if (tables.placed_bytes > kMaxSharedTableBytes)
    throw Error(std::string(name) + ": " + std::to_string(tables.placed_bytes) +
                " bytes of tables placed in shared memory, more than the " +
                std::to_string(kMaxSharedTableBytes) + " a block may take");
  static const cudaError_t consent = [] {
    const cudaError_t e = cudaFuncSetAttribute(tables_parallel_for_kernel<kMinBlocks, F>,
                                               cudaFuncAttributeMaxDynamicSharedMemorySize,
                                               int(kMaxSharedTableBytes));
    if (e != cudaSuccess) cudaGetLastError();  // not sticky: leave no error for the next check
    return e;
  }();
  if (consent != cudaSuccess && tables.placed_bytes > 48 * 1024)
    check_cuda(consent,
               (std::string(name) + ": " + std::to_string(tables.placed_bytes) +
                " bytes of shared memory per block")
                   .c_str(),
               __FILE__, __LINE__);
  const int block_size = spread_block_size(n, kBoundedBlock);
  const int64_t blocks = (n + block_size - 1) / block_size;
  if (blocks > int64_t(INT32_MAX))
    throw Error(std::string(name) + ": " + std::to_string(n) +
                " threads need more blocks than one launch can hold (2^31 - 1)");
  KernelTimingScope timing(name, block_size);
  tables_parallel_for_kernel<kMinBlocks>
      <<<unsigned(blocks), block_size, size_t(tables.placed_bytes)>>>(n, tables, body);
  check_cuda(cudaGetLastError(), name, __FILE__, __LINE__);
  timing.finish();
}

}  // namespace dv
