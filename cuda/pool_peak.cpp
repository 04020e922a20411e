// The default memory pool's high-water marks and its trimming (see pool_peak.h).
#include "cuda/pool_peak.h"

#if defined(DEEPVOX_WITH_CUDA)
#include <cuda_runtime.h>
#endif

namespace dv {

nlohmann::json DevicePoolPeak::stats() const {
  return {{"peak_used_bytes", used_bytes},
          {"peak_reserved_bytes", reserved_bytes},
          {"used_bytes", used_now_bytes},
          {"reserved_bytes", reserved_now_bytes}};
}

#if defined(DEEPVOX_WITH_CUDA)

namespace {

cudaMemPool_t default_pool() {
  int device = 0;
  cudaMemPool_t pool = nullptr;
  if (cudaGetDevice(&device) != cudaSuccess ||
      cudaDeviceGetDefaultMemPool(&pool, device) != cudaSuccess) {
    cudaGetLastError();
    return nullptr;
  }
  return pool;
}

int64_t pool_attribute(cudaMemPool_t pool, cudaMemPoolAttr attribute) {
  uint64_t value = 0;
  if (cudaMemPoolGetAttribute(pool, attribute, &value) != cudaSuccess) {
    cudaGetLastError();
    return 0;
  }
  return int64_t(value);
}

}  // namespace

DevicePoolPeak device_pool_peak() {
  DevicePoolPeak peak;
  const cudaMemPool_t pool = default_pool();
  if (!pool) return peak;
  peak.used_bytes = pool_attribute(pool, cudaMemPoolAttrUsedMemHigh);
  peak.reserved_bytes = pool_attribute(pool, cudaMemPoolAttrReservedMemHigh);
  peak.used_now_bytes = pool_attribute(pool, cudaMemPoolAttrUsedMemCurrent);
  peak.reserved_now_bytes = pool_attribute(pool, cudaMemPoolAttrReservedMemCurrent);
  return peak;
}

void reset_device_pool_peak() {
  const cudaMemPool_t pool = default_pool();
  if (!pool) return;
  uint64_t zero = 0;  // the only value these attributes accept: the mark restarts from now
  if (cudaMemPoolSetAttribute(pool, cudaMemPoolAttrUsedMemHigh, &zero) != cudaSuccess ||
      cudaMemPoolSetAttribute(pool, cudaMemPoolAttrReservedMemHigh, &zero) != cudaSuccess)
    cudaGetLastError();
}

void trim_device_pool() {
  const cudaMemPool_t pool = default_pool();
  if (pool && cudaMemPoolTrimTo(pool, 0) != cudaSuccess) cudaGetLastError();
}

#else

DevicePoolPeak device_pool_peak() {
  return {};
}
void reset_device_pool_peak() {}
void trim_device_pool() {}

#endif

}  // namespace dv
