// Atomics usable on both sides: CUDA's atomic intrinsics in device code, std::atomic_ref on
// CPU threads. Shared kernels call these and never the platform functions directly.
#pragma once

#include <cstdint>

#include "core/hd.h"

#if !DV_IN_DEVICE_CODE
#include <atomic>
#endif
#if defined(__CUDACC__)
#include <cooperative_groups.h>
#include <cooperative_groups/reduce.h>
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

// atomic_add / atomic_max from many threads onto few hot addresses: on the device the active
// lanes of a warp that target the same address combine their values first and one of them
// does the atomic (one per warp and address instead of one per thread); on the host they are
// the plain atomics. The add skips a zero sum.
template <class T>
DV_HD void atomic_add_combined(T* address, T value) {
#if DV_IN_DEVICE_CODE
  namespace cg = cooperative_groups;
  const cg::coalesced_group peers = cg::labeled_partition(cg::coalesced_threads(), address);
  const T sum = cg::reduce(peers, value, cg::plus<T>());
  if (peers.thread_rank() == 0 && sum != T(0)) atomicAdd(address, sum);
#else
  if (value != T(0)) atomic_add(address, value);
#endif
}

template <class T>
DV_HD void atomic_max_combined(T* address, T value) {
#if DV_IN_DEVICE_CODE
  namespace cg = cooperative_groups;
  const cg::coalesced_group peers = cg::labeled_partition(cg::coalesced_threads(), address);
  const T most = cg::reduce(peers, value, cg::greater<T>());
  if (peers.thread_rank() == 0) atomicMax(address, most);
#else
  atomic_max(address, value);
#endif
}

// Lets other threads run while this one spin-waits (a short sleep on the device).
DV_HD inline void spin_pause() {
#if DV_IN_DEVICE_CODE
  __nanosleep(32);
#endif
}

}  // namespace dv
