// Raw device-memory calls behind a plain C++ interface, so host code compiled by g++ can own
// GPU buffers. Implemented with the CUDA runtime when the build has CUDA; otherwise every call
// that needs a GPU throws an Error that says so.
#pragma once

#include <cstddef>
#include <string>

namespace dv {

// True when a CUDA device can be used now; `why_not` (if given) receives the reason otherwise.
bool cuda_device_available(std::string* why_not = nullptr);
std::string cuda_device_name();

// What run metadata records about the CUDA side: versions as CUDA encodes them (12040 = 12.4),
// the device's peak SM and memory clocks in MHz. Throws Error without a usable device (or in a
// CPU-only build).
struct CudaDeviceInfo {
  std::string name;
  int runtime_version = 0;
  int driver_version = 0;
  int sm_clock_max_mhz = 0;
  int memory_clock_max_mhz = 0;
  int multiprocessors = 0;
  size_t memory_bytes = 0;
};
CudaDeviceInfo cuda_device_info();

void* device_allocate(size_t bytes, const char* what);
// Bytes the device can still hand out: free device memory plus what the memory pool holds
// unused.
size_t device_free_bytes();
void device_free(void* ptr) noexcept;
void copy_to_device(void* dst, const void* src, size_t bytes);
void copy_to_host(void* dst, const void* src, size_t bytes);
void device_memset(void* dst, int value, size_t bytes);
// Waits for all launched work; throws naming `what` if a kernel failed.
void device_synchronize(const char* what);

}  // namespace dv
