// Bit counting for packed bit masks (voxel columns, occupancy slices) on both sides: the
// hardware population count in device code, std::popcount on the host.
#pragma once

#include <bit>
#include <cstdint>

#include "core/hd.h"

namespace dv {

DV_HD inline int bit_count(uint32_t v) {
#if DV_IN_DEVICE_CODE
  return __popc(v);
#else
  return std::popcount(v);
#endif
}

// The bits of `word` below bit `n` (n in [0, 32]).
DV_HD inline uint32_t bits_below(uint32_t word, int n) {
  return n >= 32 ? word : word & ((1u << n) - 1u);
}

}  // namespace dv
