// Starts the CUDA driver on a background thread while a command parses its input: cuInit and the
// primary context take a large part of a short command's time before any kernel runs, and file
// loading, volume generation and BVH building need no device. Overlapping the two takes the
// shorter of them off a process's wall time. The first CUDA call on another thread simply
// waits for the context this thread is creating.
#pragma once

#include <thread>

namespace dv {

class CudaWarmup {
 public:
  // Starts the warm-up when `wanted` and the build has CUDA; otherwise does nothing.
  explicit CudaWarmup(bool wanted);
  // Waits for the warm-up (its errors are left for the command's own CUDA calls to report).
  ~CudaWarmup();
  CudaWarmup(const CudaWarmup&) = delete;
  CudaWarmup& operator=(const CudaWarmup&) = delete;

 private:
  std::thread thread_;
};

}  // namespace dv
