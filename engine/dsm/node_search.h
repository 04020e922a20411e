// Evaluating one texel's stored visibility function V' at a depth z, shared by every storage
// strategy that can reach node k directly (compact, texture3d, blocked): Knecht eq. 3.7's clamp
// rules (before the first node: lit; after the last: the last value), linear interpolation
// between the two bracketing nodes, and at a twin depth (a surface step) the value before the
// step, as the oracle counts only crossings strictly between light and point. The bracketing
// node is found by binary search, or (coherent lookups along one camera ray) by a forward or
// backward walk from the node the previous lookup ended at. Host and device code.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "cuda/read_only.h"

namespace dv {

// One node as stored: depth from the light and visibility (1 - accumulated opacity). Aligned to
// its size, so that a lookup reads it with one vector load (cuda/read_only.h).
struct alignas(8) DsmNode {
  float z;
  float v;
};

// Node accessors for the search templates below (named structs, not lambdas: see
// engine/raster/raster_fragments.h for why); lookups only, through the read-only data path.
struct ContiguousNodes {  // node k at base[k]
  const DsmNode* base;
  DV_HD DsmNode operator()(int k) const { return read_only(base + k); }
};
struct StridedNodes {  // node k at base[k * stride]
  const DsmNode* base;
  int64_t stride;
  DV_HD DsmNode operator()(int k) const { return read_only(base + int64_t(k) * stride); }
};

// The first k in [0, count] with node(k).z >= z (count when every node lies before z).
template <class NodeAt>
DV_HD int lower_bound_nodes(const NodeAt& node, int count, float z) {
  int lo = 0, hi = count;
  while (lo < hi) {
    const int mid = (lo + hi) >> 1;
    if (node(mid).z < z)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

// The same, walking from `hint` (the previous answer for this texel, or < 0 for none).
template <class NodeAt>
DV_HD int coherent_lower_bound(const NodeAt& node, int count, float z, int hint) {
  if (hint < 0 || hint > count) return lower_bound_nodes(node, count, z);
  int k = hint;
  while (k > 0 && node(k - 1).z >= z) --k;
  while (k < count && node(k).z < z) ++k;
  return k;
}

// V'(z) on the segment from node b to node e, b.z < z <= e.z (at e.z exactly: e's value).
DV_HD inline float interpolate_between(const DsmNode& b, const DsmNode& e, float z) {
  if (z == e.z) return e.v;
  return b.v + (e.v - b.v) * ((z - b.z) / (e.z - b.z));
}

// V'(z) given k = lower bound of z (node(k - 1).z < z <= node(k).z).
template <class NodeAt>
DV_HD float interpolate_nodes(const NodeAt& node, int count, int k, float z) {
  if (k == 0) return 1.0f;
  if (k == count) return node(k - 1).v;
  return interpolate_between(node(k - 1), node(k), z);
}

template <class NodeAt>
DV_HD float evaluate_nodes(const NodeAt& node, int count, float z, int& hint) {
  const int k = coherent_lower_bound(node, count, z, hint);
  hint = k;
  return interpolate_nodes(node, count, k, z);
}

}  // namespace dv
