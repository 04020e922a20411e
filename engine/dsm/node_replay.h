// Walking each texel once for the storages that read its nodes twice (a counting or range pass
// sizes what a write pass then fills: compact, blocked, chunked, moments, fourier, occupancy).
// The first pass keeps each texel's compressed nodes in scratch chunks as the compressor emits
// them; the write pass replays them into the storage's sink instead of walking the texel's ray
// through the scene again. The walk is what generation costs (most of a pass, and a two-pass
// storage would pay it twice); a replay is only a copy. The compressor's
// output does not depend on what its sink takes (engine/dsm/visibility_compressor.h), so a replayed
// texel gets the very nodes and record that a second walk at the same eps would give.
//
// Layout: chunks of kReplayChunkNodes nodes. The replay covers the texels from first_texel on (a
// generation's, or one set of its faces'), texel t at slot t.index - first_texel: its record in
// `kept` and its first chunk at that slot; a deeper texel
// claims more from its stripe and links them (`next`). The stripes split the further chunks, each
// with its own counter on its own 64-byte line, a texel's stripe by its generation block
// (neighbouring blocks in different stripes): one counter made the CPU threads take turns on its
// cache line. A texel that finds its stripe full is listed as lost and walked again by a kernel
// of its own after the replay (strategies/storage/replay_write.h): a short pool costs time, never
// nodes. The first pass is slower than the counting pass it replaces, by its node stores (kept
// in a local array or written to the chunks alike; results/perf/rounds/09-dsm-node-replay has the
// times), and the keep stays inline: an out-of-line call made the pass several times slower.
// Host and device code; strategies/storage/node_replay_scratch.h owns the buffers.
#pragma once

#include <cstdint>
#include <vector>

#include "core/atomic.h"
#include "core/hd.h"
#include "cuda/buffer.h"
#include "engine/dsm/dsm_generator.h"
#include "engine/dsm/node_search.h"

namespace dv {

inline constexpr int kReplayChunkNodes = 4;  // fig56 at 1024^2: 2.4 nodes a texel that has any
inline constexpr int kReplayStripes = 64;
inline constexpr int kReplayCounterStride = 8;  // unsigned long longs: 64 bytes
// Counters of a replay: chunks a stripe was asked for (also beyond its share), then the texels
// walked again (at kReplayLostCounter).
inline constexpr int64_t kReplayLostCounter = int64_t(kReplayStripes) * kReplayCounterStride;
inline constexpr int64_t kReplayCounters = kReplayLostCounter + kReplayCounterStride;

// Chunks of a replay over `texels` texels whose stripes hold `stripe_chunks` each.
DV_HD inline int64_t replay_chunks(int64_t texels, int64_t stripe_chunks) {
  return texels + stripe_chunks * kReplayStripes;
}

// What a texel's first walk left for its replay.
struct KeptTexel {
  int32_t nodes = 0;
  float error = 0.0f;  // the compressed function's error bound reached (the record's)
  float final_visibility = 1.0f;
  uint32_t flags = 0;  // kKeptWalkOverflow, kKeptLost
};
inline constexpr uint32_t kKeptWalkOverflow = 1u;  // the record's kDsmWalkOverflow
inline constexpr uint32_t kKeptLost = 2u;          // its stripe was full: walk it again

// The first pass's sink: forwards every node to `inner` (a sink that never refuses: counting,
// depth range) and writes it into the texel's chunks.
template <class Inner>
struct KeepingSink {
  Inner inner;
  DsmNode* nodes = nullptr;  // null: keeps nothing (an inactive replay)
  int32_t* next = nullptr;
  unsigned long long* stripe_claims = nullptr;
  int32_t stripe_first = 0;   // the stripe's first chunk
  int32_t stripe_chunks = 0;  // and how many it has
  int32_t chunk = 0;          // the chunk being filled
  int32_t count = 0;
  bool lost = false;

  DV_HD bool emit(float z, float v) {
    const int slot = count % kReplayChunkNodes;
    if (nodes && count > 0 && slot == 0) {
      // A lost texel still asks, so that the counters tell the next pool what was needed.
      const unsigned long long k = atomic_add(stripe_claims, 1ull);
      lost |= k >= (unsigned long long)stripe_chunks;
      if (!lost) {
        next[chunk] = stripe_first + int32_t(k);
        chunk = stripe_first + int32_t(k);
      }
    }
    if (nodes && !lost) nodes[int64_t(chunk) * kReplayChunkNodes + slot] = {z, v};
    ++count;
    return inner.emit(z, v);
  }
};

// What a first pass's counters (read back) say.
struct ReplayClaims {
  int64_t asked = 0;           // further chunks asked for, all stripes
  int64_t largest_stripe = 0;  // the most one stripe asked for
  int64_t walked = 0;          // texels lost
};

inline ReplayClaims replay_claims(const std::vector<unsigned long long>& counters) {
  ReplayClaims c;
  for (int s = 0; s < kReplayStripes; ++s) {
    const int64_t stripe = int64_t(counters[size_t(s) * kReplayCounterStride]);
    c.asked += stripe;
    c.largest_stripe = stripe > c.largest_stripe ? stripe : c.largest_stripe;
  }
  c.walked = int64_t(counters[size_t(kReplayLostCounter)]);
  return c;
}

struct NodeReplay {
  View<DsmNode> nodes;   // chunks: one per texel, then kReplayStripes stripes of stripe_chunks
  View<int32_t> next;    // per chunk: the chunk after it
  View<KeptTexel> kept;  // per texel; empty: nothing is kept or replayed
  View<int32_t> lost;    // per texel: the generator threads of the lost texels, as many as counted
  View<unsigned long long> counters;  // kReplayCounters
  int32_t stripe_chunks = 0;
  int64_t first_texel = 0;  // the texel at slot 0

  DV_HD bool active() const { return kept.size > 0; }
  DV_HD int64_t slot(const DsmTexel& t) const { return t.index - first_texel; }
  DV_HD bool is_lost(const DsmTexel& t) const { return (kept[slot(t)].flags & kKeptLost) != 0; }
  // How many texels the first pass lost (their threads: lost[0, lost_count())).
  DV_HD unsigned long long lost_count() const { return counters[kReplayLostCounter]; }

  // The first pass's sink for texel t.
  template <class Inner>
  DV_HD KeepingSink<Inner> sink(const DsmTexel& t, Inner inner = Inner{}) const {
    KeepingSink<Inner> s{inner};
    if (!active()) return s;
    const int stripe = (t.x / kDsmBlockSide + t.y / kDsmBlockSide + t.face) % kReplayStripes;
    s.nodes = nodes.data;
    s.next = next.data;
    s.stripe_claims = &counters[int64_t(stripe) * kReplayCounterStride];
    s.stripe_first = int32_t(kept.size) + stripe * stripe_chunks;
    s.stripe_chunks = stripe_chunks;
    s.chunk = int32_t(slot(t));
    return s;
  }

  // First pass: texel t, of generator thread `thread`, walked into sink(t) gave `r`.
  template <class Inner>
  DV_HD void keep(int64_t thread, const DsmTexel& t,
                  const DsmTexelResult<KeepingSink<Inner>>& r) const {
    if (!active()) return;
    uint32_t flags = (r.record.flags & kDsmWalkOverflow) ? kKeptWalkOverflow : 0u;
    if (r.sink.lost) {
      flags |= kKeptLost;
      const unsigned long long k = atomic_add(&counters[kReplayLostCounter], 1ull);
      lost[int64_t(k)] = int32_t(thread);
    }
    kept[slot(t)] = {r.record.nodes, r.record.error, r.final_visibility, flags};
  }

  // Write pass: texel t's function into `sink`, as g.generate(t, eps, sink) gives it, eps being
  // the first pass's. kWalk: walked again (a lost texel, or every texel of an inactive replay);
  // else replayed (a kept texel). Two instantiations, so that the replaying kernel does not carry
  // the walk's code: with it, its registers and stack made compact's write pass several times
  // slower (results/perf/rounds/10-replay-without-walk). Reads only what the first pass wrote, so a
  // write pass may run again (chunked's retries).
  template <bool kWalk, class Sink>
  DV_HD DsmTexelResult<Sink> generate(const DsmGenerator& g, const DsmTexel& t, float eps,
                                      Sink sink) const {
    if constexpr (kWalk) {
      return g.generate(t, eps, sink);
    } else {
      const KeptTexel k = kept[slot(t)];
      TrackingSink<Sink> tracked{sink};
      int64_t chunk = slot(t);
      for (int n = 0; n < k.nodes; ++n) {
        const int slot = n % kReplayChunkNodes;
        if (n > 0 && slot == 0) chunk = next[chunk];
        const DsmNode node = nodes[chunk * kReplayChunkNodes + slot];
        if (!tracked.emit(node.z, node.v)) break;
      }
      return {tracked.inner,
              DsmGenerator::texel_record(k.nodes, k.error, tracked, k.final_visibility,
                                         (k.flags & kKeptWalkOverflow) != 0),
              k.final_visibility};
    }
  }
};

}  // namespace dv
