// Per-kernel timing totals (see kernel_timing.h).
#include "cuda/kernel_timing.h"

#include <cstdlib>
#include <cstring>
#include <mutex>

namespace dv {

namespace {

bool enabled_by_environment() {
  const char* env = std::getenv("DEEPVOX_KERNEL_TIMING");
  return env && env[0] != '\0' && std::strcmp(env, "0") != 0;
}

struct TimingState {
  std::mutex mutex;
  bool enabled = enabled_by_environment();
  std::vector<KernelTiming> totals;
};

TimingState& state() {
  static TimingState s;
  return s;
}

}  // namespace

bool kernel_timing_enabled() {
  std::lock_guard lock(state().mutex);
  return state().enabled;
}

void set_kernel_timing(bool on) {
  std::lock_guard lock(state().mutex);
  state().enabled = on;
}

std::vector<KernelTiming> kernel_timings() {
  std::lock_guard lock(state().mutex);
  return state().totals;
}

void reset_kernel_timings() {
  std::lock_guard lock(state().mutex);
  state().totals.clear();
}

nlohmann::json kernel_timings_json() {
  nlohmann::json out = nlohmann::json::array();
  for (const KernelTiming& k : kernel_timings())
    out.push_back({{"name", k.name},
                   {"launches", k.launches},
                   {"ms", k.milliseconds},
                   {"block_size", k.block_size}});
  return out;
}

KernelTimingScope::KernelTimingScope(const char* name, int block_size)
    : name_(name), block_size_(block_size) {
  if (kernel_timing_enabled()) timer_.emplace(Backend::cuda);
}

void KernelTimingScope::finish() {
  if (!timer_) return;
  const double ms = timer_->stop();
  std::lock_guard lock(state().mutex);
  for (KernelTiming& k : state().totals)
    if (k.name == name_) {
      k.launches += 1;
      k.milliseconds += ms;
      k.block_size = block_size_;
      return;
    }
  state().totals.push_back({name_, 1, ms, block_size_});
}

}  // namespace dv
