// Kernel side of the `avsm` storage: Adaptive Volumetric Shadow Maps (Salvi, Vidimce, Lauritzen
// and Lefohn 2010, HPG; the variant Unreal Engine's heterogeneous volumes use, fed in depth
// order). Every texel holds exactly N nodes (N = `nodes`, 2..32; 4, 8, 16 in the papers and the
// suites), 8 bytes each: 8 N bytes per texel, 32 / 64 / 128 bytes for N = 4 / 8 / 16, no counts
// and no pool. Generation streams the texel's exact visibility function (the eps = 0 compressor's
// nodes) into a working array of N + 1 nodes; whenever it holds N + 1, the interior node whose
// removal changes the area under the visibility curve least is dropped (the area between the
// curves with and without node k is the triangle of nodes k - 1, k, k + 1). The first node
// (where light starts to fall) and the newest one (the curve's end) are never dropped, so V'
// keeps V's support and final value. The error is not bounded by a parameter: each texel
// records the sum over its removals of the largest change a removal made (|v_k - the chord of
// its neighbours at z_k|), by the triangle inequality a bound on max |V' - V|; the experiments
// measure the error reached against the oracle. Lookups: V'(z) with node_search.h's rules over
// the N stored nodes (unused slots repeat the last node; an empty texel is N lit nodes at the
// largest float). Only float compares, multiplies and adds decide which node goes, so CPU and
// CUDA drop the same nodes. Host and device code.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "core/math.h"
#include "cuda/buffer.h"
#include "engine/dsm/node_search.h"

namespace dv {

inline constexpr int kAvsmMaxNodes = 32;
inline constexpr float kAvsmEmptyDepth = 3.402823466e38f;  // the largest float: never reached

// Streaming insertion with area-based removal into N + 1 working nodes; never refuses.
struct AvsmSink {
  int capacity = 0;  // N
  int count = 0;
  int dropped = 0;              // nodes removed so far
  float dropped_change = 0.0f;  // sum of each removal's largest change of V'
  DsmNode node[kAvsmMaxNodes + 1] = {};

  DV_HD bool emit(float z, float v) {
    node[count++] = {z, v};
    if (count > capacity) drop_least_area_node();
    return true;
  }

  // Twice the area between the curve with and without interior node k.
  DV_HD float doubled_area_change(int k) const {
    const DsmNode& a = node[k - 1];
    const DsmNode& b = node[k];
    const DsmNode& c = node[k + 1];
    const float cross = (b.z - a.z) * (c.v - a.v) - (c.z - a.z) * (b.v - a.v);
    return cross < 0.0f ? -cross : cross;
  }

  // The largest |V' change| removing interior node k makes: at z_k, against the chord of its
  // neighbours (a step at z_k's neighbour depth takes that neighbour's value).
  DV_HD float value_change(int k) const {
    const DsmNode& a = node[k - 1];
    const DsmNode& b = node[k];
    const DsmNode& c = node[k + 1];
    if (c.z == a.z) return 0.0f;  // three nodes at one depth: the middle one is never read
    const float chord = a.v + (c.v - a.v) * ((b.z - a.z) / (c.z - a.z));
    const float change = b.v - chord;
    return change < 0.0f ? -change : change;
  }

  DV_HD void drop_least_area_node() {
    int best = 1;
    float best_area = doubled_area_change(1);
    for (int k = 2; k < count - 1; ++k) {
      const float area = doubled_area_change(k);
      if (area < best_area) best = k, best_area = area;
    }
    dropped_change = min_value(dropped_change + value_change(best), 1.0f);
    ++dropped;
    for (int k = best; k < count - 1; ++k) node[k] = node[k + 1];
    --count;
  }

  // Writes the N slots of a texel: the nodes, then the last node repeated (lit if none).
  DV_HD void store(DsmNode* out) const {
    const DsmNode fill = count > 0 ? node[count - 1] : DsmNode{kAvsmEmptyDepth, 1.0f};
    for (int k = 0; k < capacity; ++k) out[k] = k < count ? node[k] : fill;
  }
};

struct AvsmReader {
  View<const DsmNode> nodes;  // texels * capacity: texel t's at [t * capacity, (t + 1) * capacity)
  int capacity = 0;

  DV_HD float visibility(int64_t texel, float z, int& hint) const {
    const ContiguousNodes node{nodes.data + texel * capacity};
    return evaluate_nodes(node, capacity, z, hint);
  }
};

}  // namespace dv
