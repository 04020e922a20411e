// CPU executor: a parallel-for over [0, n) on a fixed set of worker threads. This is the
// reference backend that CI runs; cuda/launch.cuh is the GPU executor of the same lambdas.
#pragma once

#include <cstdint>
#include <functional>

namespace dv {

// Threads used by the CPU backend: DEEPVOX_THREADS if set, else the hardware concurrency.
int cpu_thread_count();

// Runs body(begin, end) over disjoint chunks covering [0, n). Exceptions thrown by a chunk are
// rethrown (the first one) after all workers stop.
void cpu_parallel_for_chunks(int64_t n, int64_t grain,
                             const std::function<void(int64_t, int64_t)>& body);

template <class F>
void cpu_parallel_for(int64_t n, F&& f, int64_t grain = 64) {
  cpu_parallel_for_chunks(n, grain, [&f](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) f(i);
  });
}

}  // namespace dv
