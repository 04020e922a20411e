// Bit counting for packed bit masks (voxel columns, occupancy slices, light lists) on both sides:
// the hardware population count and lowest set bit in device code, std::popcount and
// std::countr_zero on the host; float bit patterns (for
// atomic maxima of non-negative floats); and the 32 x 32 bit transpose that turns 32 words of
// 32 slices into 32 masks of one slice (binvox writing).
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

// Index of the lowest set bit of v (v != 0).
DV_HD inline int lowest_bit(uint32_t v) {
#if DV_IN_DEVICE_CODE
  return __ffs(v) - 1;
#else
  return std::countr_zero(v);
#endif
}

// The bits of `word` below bit `n` (n in [0, 32]).
DV_HD inline uint32_t bits_below(uint32_t word, int n) {
  return n >= 32 ? word : word & ((1u << n) - 1u);
}

// The bit pattern of a float, and the float of a bit pattern. Non-negative floats order like
// their patterns, so an integer atomic max of patterns is a max of the values.
DV_HD inline uint32_t float_bits(float v) {
#if DV_IN_DEVICE_CODE
  return __float_as_uint(v);
#else
  return std::bit_cast<uint32_t>(v);
#endif
}
DV_HD inline float bits_float(uint32_t bits) {
#if DV_IN_DEVICE_CODE
  return __uint_as_float(bits);
#else
  return std::bit_cast<float>(bits);
#endif
}

// Transposes a 32 x 32 bit matrix in place: afterwards bit j of a[i] is what bit i of a[j]
// was (five rounds of block swaps, Hacker's Delight §7-3 with the low bit first).
DV_HD inline void transpose_bits32(uint32_t a[32]) {
  uint32_t mask = 0x0000FFFFu;
  for (int j = 16; j != 0; j >>= 1, mask ^= mask << j)
    for (int k = 0; k < 32; k = (k + j + 1) & ~j) {
      const uint32_t t = ((a[k] >> j) ^ a[k + j]) & mask;
      a[k] ^= t << j;
      a[k + j] ^= t;
    }
}

}  // namespace dv
