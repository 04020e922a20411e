// Kernel side of the `compact` storage (ours, the yardstick): a counting pass gives each texel's
// node count, a scan turns the counts into starts, and a second pass packs every node into one
// exact-size array; zero waste in the nodes, lookups by binary search. The starts are two-level,
// so a texel costs 4 bytes of index instead of 8: a 64-bit start per group of
// kCompactGroupTexels texels and a 32-bit start within its group per texel (112 maps of 512^2:
// 121 instead of 235 MB beside 140 MB of nodes). Host and device code.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "cuda/buffer.h"
#include "cuda/read_only.h"
#include "engine/dsm/node_search.h"

namespace dv {

inline constexpr int64_t kCompactGroupTexels = 64;

// Groups of `texels` texels: the start of index `texels` (the end of the last texel) has a
// group too.
DV_HD inline int64_t compact_groups(int64_t texels) {
  return texels / kCompactGroupTexels + 1;
}

// Where each texel's nodes start: texel t's nodes are [start(t), start(t + 1)).
struct CompactStarts {
  View<const int64_t> group_starts;   // compact_groups(texels): nodes before each group
  View<const uint32_t> local_starts;  // texels + 1: nodes before the texel within its group

  DV_HD int64_t start(int64_t texel) const {
    return read_only(group_starts.data + texel / kCompactGroupTexels) +
           int64_t(read_only(local_starts.data + texel));
  }
};

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
  CompactStarts starts;
  View<const DsmNode> nodes;

  DV_HD float visibility(int64_t texel, float z, int&) const {
    const int64_t begin = starts.start(texel);
    const int count = int(starts.start(texel + 1) - begin);
    const ContiguousNodes node{nodes.data + begin};
    return interpolate_nodes(node, count, lower_bound_nodes(node, count, z), z);
  }
};

}  // namespace dv
