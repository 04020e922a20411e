// Per-kernel timing of the CUDA executor: off by default (launches stay asynchronous); on with
// set_kernel_timing(true) or DEEPVOX_KERNEL_TIMING=1, every parallel_for launch is bracketed by
// CUDA events, waited for, and its milliseconds added to its kernel name's totals. `render`
// and `voxelize` put the totals in their stats JSON under "kernels" when it is on.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cuda/pass_timer.h"

namespace dv {

struct KernelTiming {
  std::string name;
  int64_t launches = 0;
  double milliseconds = 0.0;  // summed over the launches
  int block_size = 0;         // threads per block the occupancy calculator chose
};

bool kernel_timing_enabled();
void set_kernel_timing(bool on);
// Totals since the last reset, in first-launch order.
std::vector<KernelTiming> kernel_timings();
void reset_kernel_timings();
nlohmann::json kernel_timings_json();

// Brackets one launch (does nothing when timing is off): construct right before the launch,
// finish() right after it.
class KernelTimingScope {
 public:
  KernelTimingScope(const char* name, int block_size);
  void finish();

 private:
  const char* name_;
  int block_size_;
  std::optional<PassTimer> timer_;
};

}  // namespace dv
