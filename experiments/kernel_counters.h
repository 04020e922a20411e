// Per-kernel counters for the GPU benchmarks: run a benchmark with DEEPVOX_KERNEL_TIMING=1
// (cuda/kernel_timing.h) and every parallel_for kernel launched in its timed loop appears as a
// counter `k_<kernel>_ms`, its milliseconds per iteration, so a pass's time can be split into
// kernels and the rest (host work, read-backs, allocations, CUB's scans and memsets between
// them). Timing each launch waits
// for it, so the benchmark's own times in such a run are not the ones to quote.
#pragma once

#include <benchmark/benchmark.h>

#include "cuda/kernel_timing.h"

namespace dv {

// Call right before the timed loop.
inline void start_kernel_counters() {
  if (kernel_timing_enabled()) reset_kernel_timings();
}

// Call right after it.
inline void add_kernel_counters(benchmark::State& state) {
  if (!kernel_timing_enabled() || state.iterations() == 0) return;
  for (const KernelTiming& k : kernel_timings())
    state.counters["k_" + k.name + "_ms"] = k.milliseconds / double(state.iterations());
}

}  // namespace dv
