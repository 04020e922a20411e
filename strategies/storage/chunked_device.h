// Kernel side of the `chunked` storage (Knecht 2011 §4.2.2, Bornik 2012 §5): chunks of L_C
// entries (depth, visibility, next chunk, next layer) taken from a global pool of C_max chunks
// by the 8x8 texel blocks of generation, at most C_B per block (Algorithm 4.1); each node's
// entry comes from a per-block counter (atomicAdd), so a texel's nodes form a linked list
// across its block's chunks. Generation writes the pool as separate arrays (coalesced); a
// re-layout pass packs the allocated chunks into one 16-byte entry per layer (the thesis's float4
// texture), and a lookup table holds each texel's first node (chunk, layer). Lookups walk the
// list. Host and device code.
#pragma once

#include <cstdint>

#include "core/atomic.h"
#include "core/hd.h"
#include "cuda/buffer.h"
#include "cuda/read_only.h"
#include "engine/dsm/node_search.h"
#include "strategies/storage/slot_claim.h"

namespace dv {

// One packed layer; chunk indices are stored + 1 (0: no next node). Aligned to its size, as is
// ChunkFirst, so that a lookup reads it with one vector load (cuda/read_only.h).
struct alignas(16) ChunkEntry {
  float z;
  float v;
  int32_t next_chunk;
  int32_t next_layer;
};

struct alignas(8) ChunkFirst {
  int32_t chunk;  // + 1; 0: the texel has no nodes
  int32_t layer;
};

// The generation-time pool and tables.
struct ChunkPool {
  View<float> depth, visibility;         // C_max * L_C each
  View<int32_t> next_chunk, next_layer;  // C_max * L_C each
  View<int32_t> block_layers;            // b_l: layers written per block
  View<int32_t> block_chunks;            // b_g: C_B slots per block (slot_claim.h values)
  View<int32_t> chunks_used;             // g_c: pool entries taken (may exceed C_max)
  View<int32_t> refused;                 // nodes refused (block full or pool exhausted)
  View<ChunkFirst> first;                // per texel
  int32_t chunk_layers;                  // L_C
  int32_t block_limit;                   // C_B
  int32_t capacity;                      // C_max
  bool racing;                           // alloc=thesis
};

struct ChunkedSink {
  ChunkPool pool;
  int64_t block;
  int64_t texel;
  int64_t previous = -1;  // the texel's last entry, to link the next one to

  DV_HD bool emit(float z, float v) {
    const int32_t slot = atomic_add(&pool.block_layers[block], int32_t(1));
    const int32_t chunk_in_block = slot / pool.chunk_layers;
    int32_t chunk = -1;
    if (chunk_in_block < pool.block_limit) {
      int32_t* entry = &pool.block_chunks[block * pool.block_limit + chunk_in_block];
      chunk = pool.racing ? claim_racing(entry, pool.chunks_used.data, pool.capacity)
                          : claim_once(entry, pool.chunks_used.data, pool.capacity);
    }
    if (chunk < 0) {
      atomic_add(pool.refused.data, int32_t(1));
      return false;
    }
    const int32_t layer = slot % pool.chunk_layers;
    const int64_t e = int64_t(chunk) * pool.chunk_layers + layer;
    pool.depth[e] = z, pool.visibility[e] = v;
    pool.next_chunk[e] = 0, pool.next_layer[e] = 0;
    if (previous >= 0)
      pool.next_chunk[previous] = chunk + 1, pool.next_layer[previous] = layer;
    else
      pool.first[texel] = {chunk + 1, layer};
    previous = e;
    return true;
  }
};

struct ChunkedReader {
  View<const ChunkEntry> entries;  // allocated chunks * L_C
  View<const ChunkFirst> first;
  int32_t chunk_layers;

  // Walks the list to the first node at or beyond z (no spatial coherence to exploit).
  DV_HD float visibility(int64_t texel, float z, int&) const {
    const ChunkFirst f = read_only(first.data + texel);
    int32_t chunk = f.chunk, layer = f.layer;
    DsmNode previous{0.0f, 1.0f};
    bool any = false;
    while (chunk > 0) {
      const ChunkEntry e = read_only(entries.data + int64_t(chunk - 1) * chunk_layers + layer);
      if (e.z >= z) return any ? interpolate_between(previous, {e.z, e.v}, z) : 1.0f;
      previous = {e.z, e.v}, any = true;
      chunk = e.next_chunk, layer = e.next_layer;
    }
    return previous.v;
  }
};

}  // namespace dv
