// Timing of one pass on its backend: CUDA events on the GPU (the time the kernels took between
// the two events, synchronised), a steady clock on the CPU.
#pragma once

#include "core/backend.h"

namespace dv {

class PassTimer {
 public:
  explicit PassTimer(Backend backend);  // starts timing
  ~PassTimer();
  PassTimer(const PassTimer&) = delete;
  PassTimer& operator=(const PassTimer&) = delete;
  // Milliseconds since construction; on CUDA waits for the work launched so far.
  double stop();

 private:
  Backend backend_;
  double start_ms_ = 0.0;
  void* start_event_ = nullptr;
  void* stop_event_ = nullptr;
};

}  // namespace dv
