// Claiming a slot of an allocation table (a block's chunk, a tile's block) from a shared pool
// with atomics, on the CPU threads or the GPU. Slot values: 0 free, -1 being allocated, -2 the
// pool ran out, k + 1 pool entry k. Two policies:
// - claim_once: the first thread to see the slot free marks it pending, takes one pool entry
//   and publishes it; the others wait for it (Bornik 2012 §5's busy wait). One pool entry per
//   slot: no waste.
// - claim_racing: Knecht 2011 Algorithm 4.1 as printed: every thread that sees the slot free
//   takes a pool entry, and only the one whose compare-and-swap lands keeps it; the others are
//   lost (the waste of Knecht Table 5.11).
// Both return the pool entry or -1 when the pool is exhausted; never an index >= capacity.
#pragma once

#include <cstdint>

#include "core/atomic.h"
#include "core/hd.h"

namespace dv {

inline constexpr int32_t kSlotFree = 0;
inline constexpr int32_t kSlotPending = -1;
inline constexpr int32_t kSlotExhausted = -2;

DV_HD inline int32_t claim_once(int32_t* slot, int32_t* pool_used, int32_t capacity) {
  int32_t value = atomic_load(slot);
  if (value == kSlotFree && atomic_cas(slot, kSlotFree, kSlotPending) == kSlotFree) {
    const int32_t entry = atomic_add(pool_used, int32_t(1));
    value = entry < capacity ? entry + 1 : kSlotExhausted;
    atomic_exchange(slot, value);
    return value > 0 ? value - 1 : -1;
  }
  while ((value = atomic_load(slot)) == kSlotPending || value == kSlotFree) spin_pause();
  return value > 0 ? value - 1 : -1;
}

DV_HD inline int32_t claim_racing(int32_t* slot, int32_t* pool_used, int32_t capacity) {
  const int32_t value = atomic_load(slot);
  if (value > 0) return value - 1;
  const int32_t entry = atomic_add(pool_used, int32_t(1));
  if (entry >= capacity) return -1;
  const int32_t before = atomic_cas(slot, kSlotFree, entry + 1);
  return before == kSlotFree ? entry : before - 1;
}

}  // namespace dv
