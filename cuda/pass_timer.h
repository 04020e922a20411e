// Timing of passes on their backend: CUDA events on the GPU (the time the kernels took between
// two events), a steady clock on the CPU. PassTimer times one pass and waits for it;
// PassTimeline times a sequence of passes with one wait at the end, so that the GPU runs them
// back to back as in an untimed run (each launch's latency hidden behind the pass before it).
#pragma once

#include <string>
#include <utility>
#include <vector>

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

class PassTimeline {
 public:
  explicit PassTimeline(Backend backend);  // the first pass starts here
  ~PassTimeline();
  PassTimeline(const PassTimeline&) = delete;
  PassTimeline& operator=(const PassTimeline&) = delete;
  // The pass that began at the previous mark (or the start) ends here, named `name`; on CUDA
  // an event is recorded after the work launched so far, without waiting.
  void mark(std::string name);
  // Waits for the work launched so far (CUDA) and returns every marked pass with its
  // milliseconds, in order; their sum is the time from the start to the last mark.
  std::vector<std::pair<std::string, double>> finish();

 private:
  std::vector<std::string> names_;
  std::vector<double> marks_ms_;  // CPU: the start, then each mark
  std::vector<void*> events_;     // CUDA: the start, then each mark (empty on the CPU)
};

}  // namespace dv
