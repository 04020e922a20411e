// Kernel side of the `occupancy` storage (occupancy maps after Sintorn & Assarsson 2009, "Hair
// self shadowing and transparency depth ordering using occupancy maps"): per texel S slices
// (32, 64 or 128) spread over the texel's own depth range [z_first, z_last] with one bit each
// (occupied: some optical depth lies in it) and K slabs (1, 2, 4 or 8 runs of S/K slices) with
// the optical depth each holds, their slab map. The optical depth in front of depth z is that of
// the slabs before z's slab plus its own slab's share by occupied slices strictly before z's
// slice: with n occupied slices before z out of m in the slab, tau_slab * n / m, which is their
// (1 - a)^n when every surface in the slab has the same alpha. A surface in z's own slice does
// not shadow z (a lit receiver on its own slice; a leak behind a surface closer than one slice).
// Media are split over the slices they cross by length, so a constant medium becomes a staircase
// of one slice's optical depth per step. The texel's last step (an opaque floor, the last sheet)
// stays out of the slabs and is applied exactly after z_last (optical_depth_basis.h), as are
// depths outside the range. Per texel kTexelHeaderFloats + K floats + S/32 words, texel t's at
// t * stride: z_first, z_last, the total optical depth, slab optical depths, slice bits.
// Host and device code.
#pragma once

#include <cstdint>
#include <cstring>

#include "core/bits.h"
#include "core/hd.h"
#include "core/math.h"
#include "cuda/buffer.h"
#include "strategies/storage/optical_depth_basis.h"

namespace dv {

inline constexpr int kMaxOccupancyWords = 4;  // 128 slices
inline constexpr int kMaxOccupancySlabs = 8;

DV_HD inline int occupancy_stride(int slices, int slabs) {
  return kTexelHeaderFloats + slabs + slices / 32;
}

// The texel's slice bits, stored as 32-bit words after the slab depths.
DV_HD inline uint32_t occupancy_word(const float* texel, int slabs, int w) {
  uint32_t word;
  memcpy(&word, texel + kTexelHeaderFloats + slabs + w, sizeof(word));
  return word;
}

// The slice of normalised depth u in [0, 1] (u = 1 in the last slice).
DV_HD inline int occupancy_slice(double u, int slices) {
  return int(clamp_value(u * slices, 0.0, double(slices - 1)));
}

DV_HD inline double occupancy_depth_u(const float* texel, float z) {
  const double span = double(texel[1]) - double(texel[0]);
  return span > 0.0 ? (double(z) - double(texel[0])) / span : 0.0;
}

struct OccupancySink {
  float* texel;  // the texel's record; z_first and z_last are already written (range pass)
  int slices;
  int slabs;
  uint32_t bits[kMaxOccupancyWords] = {};
  double slab_depth[kMaxOccupancySlabs] = {};
  OpticalDepthPieces pieces;

  DV_HD bool emit(float z, float v) {
    pieces.last_z = texel[1];
    pieces.push(z, v, *this);
    return true;
  }
  DV_HD void occupy(int slice, double mass) {
    bits[slice >> 5] |= 1u << (slice & 31);
    slab_depth[slice / (slices / slabs)] += mass;
  }
  // A point mass (z0 == z1) in its slice; a uniform density over [z0, z1] split by length.
  DV_HD void add(float z0, float z1, double mass) {
    const double u0 = occupancy_depth_u(texel, z0), u1 = occupancy_depth_u(texel, z1);
    const int first = occupancy_slice(u0, slices), last = occupancy_slice(u1, slices);
    if (first == last || !(u1 > u0)) {
      occupy(last, mass);
      return;
    }
    for (int s = first; s <= last; ++s) {
      const double lo = max_value(u0, double(s) / slices);
      const double hi = s == last ? u1 : min_value(u1, double(s + 1) / slices);
      if (hi > lo) occupy(s, mass * (hi - lo) / (u1 - u0));
    }
  }
  DV_HD void write() const {
    texel[2] = float(pieces.tau);
    for (int k = 0; k < slabs; ++k) texel[kTexelHeaderFloats + k] = float(slab_depth[k]);
    for (int w = 0; w < slices / 32; ++w)
      memcpy(texel + kTexelHeaderFloats + slabs + w, &bits[w], sizeof(uint32_t));
  }
};

// Occupied slices of slab `slab` strictly before slice `end` (end may lie past the slab).
DV_HD inline int occupied_slices(const float* texel, int slices, int slabs, int slab, int end) {
  const int per_slab = slices / slabs;
  const int first = slab * per_slab, stop = min_value(end, first + per_slab);
  int count = 0;
  for (int s = first; s < stop;) {
    const int w = s >> 5, bit = s & 31, n = min_value(32 - bit, stop - s);
    count += bit_count(bits_below(occupancy_word(texel, slabs, w) >> bit, n));
    s += n;
  }
  return count;
}

struct OccupancyReader {
  View<const float> data;  // texels * occupancy_stride(slices, slabs)
  int slices = 64;
  int slabs = 4;

  DV_HD float visibility(int64_t t, float z, int&) const {
    const float* texel = data.data + t * occupancy_stride(slices, slabs);
    float outside;
    if (visibility_outside_range(texel, z, outside)) return outside;
    const int slice = occupancy_slice(occupancy_depth_u(texel, z), slices);
    const int slab = slice / (slices / slabs);
    double tau = 0.0;
    for (int k = 0; k < slab; ++k) tau += double(texel[kTexelHeaderFloats + k]);
    const int occupied = occupied_slices(texel, slices, slabs, slab, slices);
    if (occupied > 0)
      tau += double(texel[kTexelHeaderFloats + slab]) *
             occupied_slices(texel, slices, slabs, slab, slice) / occupied;
    return float(exp(-tau));
  }
};

}  // namespace dv
