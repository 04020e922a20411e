// parallel_for_with_tables: parallel_for_bounded whose body reads tables that every thread reads
// again and again (cuda/shared_tables.h), copied into each CUDA block's shared memory first.
#pragma once

#include <cstdint>
#include <string>

#include "core/backend.h"
#include "core/error.h"
#include "core/hd.h"
#include "core/parallel.h"
#include "cuda/execute.h"
#include "cuda/shared_tables.h"

#if defined(__CUDACC__)
#include "cuda/tables_launch.cuh"
#endif

namespace dv {

// Bytes of shared memory a block of a kernel at kMinBlocks blocks per SM may give to tables
// (cuda/tables_launch.cuh); 0 on the CPU, where nothing is copied.
template <int kMinBlocks>
int64_t shared_table_budget(Backend backend) {
#if defined(__CUDACC__)
  if (backend == Backend::cuda) return cuda_shared_table_budget(kMinBlocks);
#endif
  (void)backend;
  return 0;
}

// body(i, nullptr) on the CPU, where the tables are read where they are.
template <class F>
struct TablesBody {
  F body;
  DV_HD void operator()(int64_t i) const { body(i, nullptr); }
};

// parallel_for_bounded<kMinBlocks> whose body(i, copy) reads `tables`, placed with
// shared_table_budget<kMinBlocks>(backend), through placed_view(view, tables.placed_offset(k),
// copy): a CUDA block first copies the placed tables into its shared memory `copy`; on the CPU
// `copy` is null.
template <int kMinBlocks, class F>
void parallel_for_with_tables(Backend backend, const char* name, int64_t n,
                              const SharedTables& tables, F body) {
  static_assert(kMinBlocks >= 1, "at least one block per SM");
#if defined(DEEPVOX_WITH_CUDA) && !defined(__CUDACC__)
  static_assert(kNeverTrue<F>,
                "this file launches parallel_for_with_tables: list it in deepvox_kernel_sources() "
                "so nvcc compiles it (scripts/cmake/DeepvoxCuda.cmake)");
#endif
  if (backend == Backend::cuda) {
#if defined(__CUDACC__)
    cuda_tables_parallel_for<kMinBlocks>(name, n, tables, body);
#else
    throw Error(std::string(name) + ": CUDA launch in a build without CUDA");
#endif
  } else {
    cpu_parallel_for(n, TablesBody<F>{body});
  }
}

}  // namespace dv
