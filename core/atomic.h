// Atomics usable on both sides: CUDA's atomic intrinsics in device code, std::atomic_ref on
// CPU threads. Shared kernels call these and never the platform functions directly.
#pragma once

#include <cstdint>
#include <type_traits>

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

// atomic_add / atomic_max from many threads onto few hot addresses: on the device the lanes of
// a warp that reach the call together and target the same address combine their values first
// (each reads its peers' values by shuffle) and the lowest of them does the one atomic; on the
// host they are the plain atomics. The add skips a zero sum.
#if DV_IN_DEVICE_CODE
__device__ inline int warp_lane() {
  unsigned lane;
  asm("mov.u32 %0, %%laneid;" : "=r"(lane));
  return int(lane);
}

// `value` of every lane here with this one that targets `address`, folded by `op` (each of
// them gets the result); `leader`: this lane is the lowest of them. A whole warp on one address
// (per-pixel and per-texel counters) folds integers in five butterfly steps instead of 31
// shuffles in lane order: integer sums and maxima do not depend on the order.
template <class T, class Op>
__device__ T combine_with_peers(const void* address, T value, Op op, bool& leader) {
  const unsigned peers =
      __match_any_sync(__activemask(), reinterpret_cast<unsigned long long>(address));
  if constexpr (std::is_integral_v<T>) {
    if (peers == 0xffffffffu) {
      T result = value;
      for (int offset = 16; offset > 0; offset /= 2)
        result = op(result, __shfl_xor_sync(peers, result, offset));
      leader = warp_lane() == 0;
      return result;
    }
  }
  T result = __shfl_sync(peers, value, __ffs(peers) - 1);
  for (unsigned rest = peers & (peers - 1); rest != 0; rest &= rest - 1)
    result = op(result, __shfl_sync(peers, value, __ffs(rest) - 1));
  leader = warp_lane() == __ffs(peers) - 1;
  return result;
}
#endif

template <class T>
DV_HD void atomic_add_combined(T* address, T value) {
#if DV_IN_DEVICE_CODE
  bool leader = false;
  const T sum = combine_with_peers(
      address, value, [](T a, T b) { return a + b; }, leader);
  if (leader && sum != T(0)) atomicAdd(address, sum);
#else
  if (value != T(0)) atomic_add(address, value);
#endif
}

template <class T>
DV_HD void atomic_max_combined(T* address, T value) {
#if DV_IN_DEVICE_CODE
  bool leader = false;
  const T most = combine_with_peers(
      address, value, [](T a, T b) { return a < b ? b : a; }, leader);
  if (leader) atomicMax(address, most);
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
