// PassTimer and PassTimeline: CUDA events or a steady clock (see pass_timer.h).
#include "cuda/pass_timer.h"

#include <chrono>

#if defined(DEEPVOX_WITH_CUDA)
#include <cuda_runtime_api.h>

#include "cuda/cuda_check.h"
#endif

namespace dv {

namespace {
double now_ms() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}
}  // namespace

PassTimer::PassTimer(Backend backend) : backend_(backend) {
#if defined(DEEPVOX_WITH_CUDA)
  if (backend_ == Backend::cuda) {
    cudaEvent_t start, stop;
    DV_CUDA_CHECK(cudaEventCreate(&start));
    DV_CUDA_CHECK(cudaEventCreate(&stop));
    DV_CUDA_CHECK(cudaEventRecord(start));
    start_event_ = start;
    stop_event_ = stop;
    return;
  }
#endif
  start_ms_ = now_ms();
}

PassTimer::~PassTimer() {
#if defined(DEEPVOX_WITH_CUDA)
  if (start_event_) cudaEventDestroy(static_cast<cudaEvent_t>(start_event_));
  if (stop_event_) cudaEventDestroy(static_cast<cudaEvent_t>(stop_event_));
#endif
}

double PassTimer::stop() {
#if defined(DEEPVOX_WITH_CUDA)
  if (backend_ == Backend::cuda) {
    auto stop = static_cast<cudaEvent_t>(stop_event_);
    DV_CUDA_CHECK(cudaEventRecord(stop));
    DV_CUDA_CHECK(cudaEventSynchronize(stop));
    float ms = 0.0f;
    DV_CUDA_CHECK(cudaEventElapsedTime(&ms, static_cast<cudaEvent_t>(start_event_), stop));
    return double(ms);
  }
#endif
  return now_ms() - start_ms_;
}

#if defined(DEEPVOX_WITH_CUDA)
namespace {
cudaEvent_t record_event() {
  cudaEvent_t event;
  DV_CUDA_CHECK(cudaEventCreate(&event));
  DV_CUDA_CHECK(cudaEventRecord(event));
  return event;
}
}  // namespace
#endif

PassTimeline::PassTimeline(Backend backend) {
#if defined(DEEPVOX_WITH_CUDA)
  if (backend == Backend::cuda) {
    events_.push_back(record_event());
    return;
  }
#endif
  (void)backend;
  marks_ms_.push_back(now_ms());
}

PassTimeline::~PassTimeline() {
#if defined(DEEPVOX_WITH_CUDA)
  for (void* e : events_) cudaEventDestroy(static_cast<cudaEvent_t>(e));
#endif
}

void PassTimeline::mark(std::string name) {
  names_.push_back(std::move(name));
#if defined(DEEPVOX_WITH_CUDA)
  if (!events_.empty()) {
    events_.push_back(record_event());
    return;
  }
#endif
  marks_ms_.push_back(now_ms());
}

std::vector<std::pair<std::string, double>> PassTimeline::finish() {
  std::vector<std::pair<std::string, double>> out;
#if defined(DEEPVOX_WITH_CUDA)
  if (!events_.empty()) {
    DV_CUDA_CHECK(cudaEventSynchronize(static_cast<cudaEvent_t>(events_.back())));
    for (size_t k = 0; k < names_.size(); ++k) {
      float ms = 0.0f;
      DV_CUDA_CHECK(cudaEventElapsedTime(&ms, static_cast<cudaEvent_t>(events_[k]),
                                         static_cast<cudaEvent_t>(events_[k + 1])));
      out.emplace_back(names_[k], double(ms));
    }
    return out;
  }
#endif
  for (size_t k = 0; k < names_.size(); ++k)
    out.emplace_back(names_[k], marks_ms_[k + 1] - marks_ms_[k]);
  return out;
}

}  // namespace dv
