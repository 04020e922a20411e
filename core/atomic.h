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

// A load that sees other threads' atomic writes (spin-waits read through it).
template <class T>
DV_HD T atomic_load(const T* address) {
#if DV_IN_DEVICE_CODE
  return *static_cast<const volatile T*>(address);
#else
  return std::atomic_ref<T>(*const_cast<T*>(address)).load(std::memory_order_acquire);
#endif
}

// Returns the previous value.
template <class T>
DV_HD T atomic_exchange(T* address, T value) {
#if DV_IN_DEVICE_CODE
  return atomicExch(address, value);
#else
  return std::atomic_ref<T>(*address).exchange(value, std::memory_order_acq_rel);
#endif
}

// Lets other threads run while this one spin-waits (a short sleep on the device).
DV_HD inline void spin_pause() {
#if DV_IN_DEVICE_CODE
  __nanosleep(32);
#endif
}

}  // namespace dv
