// Pre-filtered deep-shadow-map texels (Lokovic & Veach 2000): K jittered sub-rays per texel
// (stratified over a sqrt(K) x sqrt(K) grid, jitter from a hash of texel and sub-ray, so CPU and
// CUDA agree), each walked through the BVH (its exact crossings; the tile lists hold pixel-centre
// coverage only) and compressed with eps / 2 into a small local array; their average
// V(z) = (1/K) sum V_k(z) is then streamed in depth order into the texel's compressor with
// eps / 2, so V' stays within eps of the average of the sub-rays' interpolants. Host and device.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "engine/dsm/node_search.h"

namespace dv {

inline constexpr int kMaxSubrays = 16;   // 1, 4, 9 or 16 sub-rays per texel
inline constexpr int kSubrayNodes = 48;  // nodes kept per sub-ray before the merge

// The nodes of each sub-ray's compressed function.
struct SubrayNodes {
  float z[kMaxSubrays][kSubrayNodes];
  float v[kMaxSubrays][kSubrayNodes];
  int count[kMaxSubrays];
  int rays = 0;
};

// Uniform in [0, 1) from a texel index and a sub-ray number (a 64-bit mix; identical on both
// backends).
DV_HD inline double subray_jitter(int64_t texel, int subray, int axis) {
  uint64_t h = uint64_t(texel) * 0x9E3779B97F4A7C15ull + uint64_t(subray * 2 + axis + 1);
  h ^= h >> 33, h *= 0xFF51AFD7ED558CCDull, h ^= h >> 33, h *= 0xC4CEB9FE1A85EC53ull, h ^= h >> 33;
  return double(h >> 11) * (1.0 / 9007199254740992.0);
}

// Streams the average of the sub-rays' functions into `target` (push): at every node depth of
// any sub-ray the average just before it and, where some sub-ray steps there, just after it.
template <class Target>
DV_HD void push_average(const SubrayNodes& s, Target& target) {
  int next[kMaxSubrays];
  for (int k = 0; k < s.rays; ++k) next[k] = 0;
  const double weight = 1.0 / double(s.rays);
  for (;;) {
    float z = 0.0f;
    bool any = false;
    for (int k = 0; k < s.rays; ++k)
      if (next[k] < s.count[k] && (!any || s.z[k][next[k]] < z)) z = s.z[k][next[k]], any = true;
    if (!any) return;
    double before = 0.0, after = 0.0;
    for (int k = 0; k < s.rays; ++k) {
      const int n = next[k], count = s.count[k];
      double left;
      if (n == 0)
        left = 1.0;
      else if (n == count)
        left = s.v[k][count - 1];
      else
        left = interpolate_between({s.z[k][n - 1], s.v[k][n - 1]}, {s.z[k][n], s.v[k][n]}, z);
      int m = n;
      while (m < count && s.z[k][m] == z) ++m;
      next[k] = m;
      before += left;
      after += m > n ? double(s.v[k][m - 1]) : left;
    }
    target.push(z, float(before * weight));
    if (after != before) target.push(z, float(after * weight));
  }
}

}  // namespace dv
