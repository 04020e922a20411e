// Kernel side of the `blocked` storage (Hadwiger et al. 2006 §3.4): the maps are split into
// tiles of T x T texels; blocks of 8 consecutive layers of a tile are taken on demand from a
// pool (a 3D texture of blocks in the paper), and an indirection table per tile names the
// block of each group of 8 layers. Memory grows with the depth complexity of each tile instead
// of the deepest texel of all maps. A per-texel layer count ends each function. Lookups: binary
// search, coherent along a camera ray like texture3d. Host and device code.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "cuda/buffer.h"
#include "cuda/read_only.h"
#include "engine/dsm/node_search.h"
#include "strategies/storage/slot_claim.h"

namespace dv {

inline constexpr int kBlockLayers = 8;

struct BlockedLayout {
  int32_t tile;            // T
  int32_t tiles_per_side;  // ceil(res / T)
  int32_t resolution;
  int32_t blocks_per_tile;  // indirection entries per tile: max layers / 8
  int64_t texels_per_face;

  DV_HD int64_t tile_of(int64_t texel) const {
    const int64_t face = texel / texels_per_face, r = texel % texels_per_face;
    const int x = int(r % resolution), y = int(r / resolution);
    return (face * tiles_per_side + y / tile) * tiles_per_side + x / tile;
  }
  DV_HD int local_of(int64_t texel) const {
    const int64_t r = texel % texels_per_face;
    return int(r / resolution % tile) * tile + int(r % resolution % tile);
  }
  // Entry of layer k of the texel at `local` in pool block `block`.
  DV_HD int64_t entry(int32_t block, int k, int local) const {
    return (int64_t(block) * kBlockLayers + k % kBlockLayers) * (int64_t(tile) * tile) + local;
  }
};

struct BlockedSink {
  BlockedLayout layout;
  View<int32_t> indirection;  // tiles * blocks_per_tile (slot_claim.h values)
  View<int32_t> blocks_used;
  View<DsmNode> pool;  // capacity * 8 * T^2
  int32_t capacity;
  int64_t tile;
  int local;
  int count = 0;

  DV_HD bool emit(float z, float v) {
    const int group = count / kBlockLayers;
    if (group >= layout.blocks_per_tile) return false;
    const int32_t block =
        claim_once(&indirection[tile * layout.blocks_per_tile + group], blocks_used.data, capacity);
    if (block < 0) return false;
    pool[layout.entry(block, count, local)] = {z, v};
    ++count;
    return true;
  }
};

// Node k of one texel through its tile's indirection table.
struct BlockedNodes {
  BlockedLayout layout;
  const int32_t* table;
  const DsmNode* pool;
  int local;
  DV_HD DsmNode operator()(int k) const {
    return read_only(pool + layout.entry(read_only(table + k / kBlockLayers) - 1, k, local));
  }
};

struct BlockedReader {
  BlockedLayout layout;
  View<const int32_t> indirection;
  View<const DsmNode> pool;
  View<const int32_t> counts;  // layers per texel

  DV_HD float visibility(int64_t texel, float z, int& hint) const {
    const BlockedNodes node{layout,
                            indirection.data + layout.tile_of(texel) * layout.blocks_per_tile,
                            pool.data, layout.local_of(texel)};
    return evaluate_nodes(node, read_only(counts.data + texel), z, hint);
  }
};

}  // namespace dv
