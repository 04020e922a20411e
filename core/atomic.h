// Atomics usable on both sides: CUDA's atomic intrinsics in device code, std::atomic_ref on
// CPU threads. Shared kernels call these and never the platform functions directly.
#pragma once

#include <cstdint>

#include "core/hd.h"

#if !DV_IN_DEVICE_CODE
#include <atomic>
#endif

namespace dv {

template <class T>
DV_HD T atomic_add(T* address, T value) {
#if DV_IN_DEVICE_CODE
  return atomicAdd(address, value);
#else
  return std::atomic_ref<T>(*address).fetch_add(value, std::memory_order_relaxed);
#endif
}

template <class T>
DV_HD T atomic_or(T* address, T value) {
#if DV_IN_DEVICE_CODE
  return atomicOr(address, value);
#else
  return std::atomic_ref<T>(*address).fetch_or(value, std::memory_order_relaxed);
#endif
}

template <class T>
DV_HD T atomic_max(T* address, T value) {
#if DV_IN_DEVICE_CODE
  return atomicMax(address, value);
#else
  std::atomic_ref<T> ref(*address);
  T old = ref.load(std::memory_order_relaxed);
  while (old < value && !ref.compare_exchange_weak(old, value, std::memory_order_relaxed)) {
  }
  return old;
#endif
}

template <class T>
DV_HD T atomic_min(T* address, T value) {
#if DV_IN_DEVICE_CODE
  return atomicMin(address, value);
#else
  std::atomic_ref<T> ref(*address);
  T old = ref.load(std::memory_order_relaxed);
  while (value < old && !ref.compare_exchange_weak(old, value, std::memory_order_relaxed)) {
  }
  return old;
#endif
}

// Returns the previous value; stores `desired` only if it was `expected`.
template <class T>
DV_HD T atomic_cas(T* address, T expected, T desired) {
#if DV_IN_DEVICE_CODE
  return atomicCAS(address, expected, desired);
#else
  std::atomic_ref<T>(*address).compare_exchange_strong(expected, desired,
                                                       std::memory_order_relaxed);
  return expected;
#endif
}

}  // namespace dv
