// The device memory deepvox held at most at once, and giving back what it holds unused: every
// device buffer (cuda/buffer.h), CUB's scratch and every pass's scratch come from the device's
// default memory pool (cuda/device_memory.cpp), so the pool's high-water marks count the whole
// process's device footprint but the CUDA context: the bytes in use at once (maps, per-texel
// records, replay scratch, tile lists, images), and the bytes the pool reserved from the device
// for them (what the process keeps: the pool returns nothing by itself, only when trimmed).
// `render --stats` reports both.
#pragma once

#include <cstdint>

#include <nlohmann/json.hpp>

namespace dv {

struct DevicePoolPeak {
  int64_t used_bytes = 0;      // most bytes in use at once since start (or the last reset)
  int64_t reserved_bytes = 0;  // most bytes the pool held from the device
  int64_t used_now_bytes = 0;
  int64_t reserved_now_bytes = 0;
  nlohmann::json stats() const;
};

// Zeros without a usable device (or in a CPU-only build).
DevicePoolPeak device_pool_peak();
// Restarts both high-water marks from the current use (a no-op without a device).
void reset_device_pool_peak();
// Gives the pool's unused memory back to the device (cudaMemPoolTrimTo, keeping nothing), so
// that a pass's scratch is not held after it; the next allocation beyond what the pool holds
// asks the device again. A no-op without a device.
void trim_device_pool();

}  // namespace dv
