// The backends a test runs on: both, always instantiated, and skipped with the reason where a
// backend cannot run here (no GPU), so a CPU-only machine reports what it did not check.
#pragma once

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cuda/device_memory.h"
#include "cuda/execute.h"

namespace dv::test {

inline std::vector<Backend> all_backends() {
  return {Backend::cpu, Backend::cuda};
}

// Empty when `backend` can run here, else why not.
inline std::string backend_unavailable(Backend backend) {
  std::string why;
  if (backend == Backend::cuda && !cuda_device_available(&why)) return "no CUDA device: " + why;
  return "";
}

}  // namespace dv::test

// Skips the current test with the reason when `backend` cannot run here.
#define DV_SKIP_UNLESS_BACKEND(backend)                                          \
  do {                                                                           \
    const std::string dv_skip_reason = ::dv::test::backend_unavailable(backend); \
    if (!dv_skip_reason.empty()) GTEST_SKIP() << dv_skip_reason;                 \
  } while (0)
