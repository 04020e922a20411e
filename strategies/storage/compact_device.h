// Kernel side of the `compact` storage (ours, the yardstick): a counting pass gives each texel's
// node count, an exclusive scan turns the counts into offsets, and a second pass packs every
// node into one exact-size array; zero waste, lookups by binary search. Host and device code.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "cuda/buffer.h"
#include "cuda/read_only.h"
#include "engine/dsm/node_search.h"

namespace dv {

// Writes one texel's nodes into its exact-size range; refuses beyond it (which only happens if
// the write pass needed more nodes than the counting pass counted).
struct CompactSink {
  DsmNode* out;
  int64_t capacity;
  int64_t count = 0;
  DV_HD bool emit(float z, float v) {
    if (count >= capacity) return false;
    out[count++] = {z, v};
    return true;
  }
};

struct CompactReader {
  View<const int64_t> offsets;  // texels + 1: texel t's nodes are [offsets[t], offsets[t + 1])
  View<const DsmNode> nodes;

  DV_HD float visibility(int64_t texel, float z, int&) const {
    const int64_t begin = read_only(offsets.data + texel);
    const int count = int(read_only(offsets.data + texel + 1) - begin);
    const ContiguousNodes node{nodes.data + begin};
    return interpolate_nodes(node, count, lower_bound_nodes(node, count, z), z);
  }
};

}  // namespace dv
