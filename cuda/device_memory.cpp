// Device memory through the CUDA runtime API (or clear errors in CPU-only builds).
#include "cuda/device_memory.h"

#include <cstdint>
#include <cstdlib>

#include "core/error.h"
#include "core/hd.h"

#if defined(DEEPVOX_WITH_CUDA)
#include <cuda_runtime_api.h>

#include "cuda/cuda_check.h"
#include "cuda/memory_check.h"
#endif

namespace dv {

#if defined(DEEPVOX_WITH_CUDA)

bool cuda_device_available(std::string* why_not) {
  int count = 0;
  cudaError_t err = cudaGetDeviceCount(&count);
  if (err != cudaSuccess) {
    if (why_not) *why_not = std::string("no usable CUDA device: ") + cudaGetErrorString(err);
    cudaGetLastError();
    return false;
  }
  if (count == 0) {
    if (why_not) *why_not = "no CUDA device present";
    return false;
  }
  return true;
}

std::string cuda_device_name() {
  int device = 0;
  DV_CUDA_CHECK(cudaGetDevice(&device));
  cudaDeviceProp prop{};
  DV_CUDA_CHECK(cudaGetDeviceProperties(&prop, device));
  return prop.name;
}

CudaDeviceInfo cuda_device_info() {
  int device = 0;
  DV_CUDA_CHECK(cudaGetDevice(&device));
  cudaDeviceProp prop{};
  DV_CUDA_CHECK(cudaGetDeviceProperties(&prop, device));
  CudaDeviceInfo info;
  info.name = prop.name;
  info.multiprocessors = prop.multiProcessorCount;
  info.memory_bytes = prop.totalGlobalMem;
  DV_CUDA_CHECK(cudaRuntimeGetVersion(&info.runtime_version));
  DV_CUDA_CHECK(cudaDriverGetVersion(&info.driver_version));
  int khz = 0;
  DV_CUDA_CHECK(cudaDeviceGetAttribute(&khz, cudaDevAttrClockRate, device));
  info.sm_clock_max_mhz = khz / 1000;
  DV_CUDA_CHECK(cudaDeviceGetAttribute(&khz, cudaDevAttrMemoryClockRate, device));
  info.memory_clock_max_mhz = khz / 1000;
  return info;
}

namespace {

// Device buffers come from the device's default memory pool, stream-ordered on the legacy
// default stream that every kernel, copy and memset here runs on; the pool keeps freed memory
// (release threshold: never), so repeated passes reuse it instead of paying cudaMalloc and the
// device-wide synchronisation of cudaFree on every call.
void retain_pool_memory() {
  static const bool configured = [] {
    int device = 0;
    cudaMemPool_t pool = nullptr;
    if (cudaGetDevice(&device) == cudaSuccess &&
        cudaDeviceGetDefaultMemPool(&pool, device) == cudaSuccess) {
      uint64_t keep = UINT64_MAX;
      cudaMemPoolSetAttribute(pool, cudaMemPoolAttrReleaseThreshold, &keep);
    }
    cudaGetLastError();
    return true;
  }();
  (void)configured;
}

}  // namespace

// A failed allocation for want of memory throws OutOfMemory (cuda/memory_check.h), naming `what`
// and the bytes; so does one beyond DEEPVOX_MEMORY_LIMIT when that is set (the check costs a
// cudaMemGetInfo, so it runs only then).
void* device_allocate(size_t bytes, const char* what) {
  void* ptr = nullptr;
  if (bytes == 0) return nullptr;
  if (std::getenv("DEEPVOX_MEMORY_LIMIT")) check_reservation(Memory::device, int64_t(bytes), what);
  retain_pool_memory();
  cudaError_t err = cudaMallocAsync(&ptr, bytes, cudaStreamLegacy);
  if (err != cudaSuccess) {
    cudaGetLastError();
    const std::string asked = format_bytes(int64_t(bytes)) + " (" + std::to_string(bytes) +
                              " bytes) asked, cudaMallocAsync failed: " + cudaGetErrorString(err);
    if (err == cudaErrorMemoryAllocation)
      throw OutOfMemory(
          what, asked + " (" + format_bytes(int64_t(device_free_bytes())) + " free on the device)",
          int64_t(bytes));
    throw Error(std::string(what) + ": " + asked);
  }
  return ptr;
}

size_t device_free_bytes() {
  size_t free = 0, total = 0;
  DV_CUDA_CHECK(cudaMemGetInfo(&free, &total));
  int device = 0;
  cudaMemPool_t pool = nullptr;
  uint64_t reserved = 0, used = 0;
  if (cudaGetDevice(&device) == cudaSuccess &&
      cudaDeviceGetDefaultMemPool(&pool, device) == cudaSuccess &&
      cudaMemPoolGetAttribute(pool, cudaMemPoolAttrReservedMemCurrent, &reserved) == cudaSuccess &&
      cudaMemPoolGetAttribute(pool, cudaMemPoolAttrUsedMemCurrent, &used) == cudaSuccess &&
      reserved > used)
    free += size_t(reserved - used);
  cudaGetLastError();
  return free;
}

void device_free(void* ptr) noexcept {
  if (ptr) cudaFreeAsync(ptr, cudaStreamLegacy);
}

void copy_to_device(void* dst, const void* src, size_t bytes) {
  if (bytes) DV_CUDA_CHECK(cudaMemcpy(dst, src, bytes, cudaMemcpyHostToDevice));
}

void copy_to_host(void* dst, const void* src, size_t bytes) {
  if (bytes) DV_CUDA_CHECK(cudaMemcpy(dst, src, bytes, cudaMemcpyDeviceToHost));
}

void device_memset(void* dst, int value, size_t bytes) {
  if (bytes) DV_CUDA_CHECK(cudaMemset(dst, value, bytes));
}

void device_synchronize(const char* what) {
  check_cuda(cudaDeviceSynchronize(), what, __FILE__, __LINE__);
}

#else

namespace {
[[noreturn]] void no_cuda(const char* call) {
  throw Error(std::string(call) +
              ": this deepvox was built without CUDA (-DDEEPVOX_CUDA=OFF or no nvcc)");
}
}  // namespace

bool cuda_device_available(std::string* why_not) {
  if (why_not) *why_not = "deepvox was built without CUDA";
  return false;
}
std::string cuda_device_name() {
  no_cuda("cuda_device_name");
}
CudaDeviceInfo cuda_device_info() {
  no_cuda("cuda_device_info");
}
void* device_allocate(size_t, const char*) {
  no_cuda("device_allocate");
}
size_t device_free_bytes() {
  no_cuda("device_free_bytes");
}
void device_free(void*) noexcept {}
void copy_to_device(void*, const void*, size_t) {
  no_cuda("copy_to_device");
}
void copy_to_host(void*, const void*, size_t) {
  no_cuda("copy_to_host");
}
void device_memset(void*, int, size_t) {
  no_cuda("device_memset");
}
void device_synchronize(const char*) {
  no_cuda("device_synchronize");
}

#endif

}  // namespace dv
