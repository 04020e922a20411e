// The buffers of a NodeReplay (engine/dsm/node_replay.h) for one generation of a storage: allocated
// when its first pass starts (inside that pass's timing: the counters' clear is GPU work), reused
// by the generation's further sets of faces where they are large enough, freed when its last
// write pass is done (device memory comes from the pool of cuda/device_memory.cpp, so this costs
// no cudaMalloc in steady state), and not part of the storage's bytes_allocated: the storage
// holds none of it between generations. A chunk per texel, and per stripe what the busiest
// stripe asked for in the set before (or the last generation's last set), an eighth more (the
// first generation: a chunk for every fourth texel, over the stripes); a record and a slot in
// the list of lost texels per texel (about kReplayBytesPerTexel a texel in all: 1.9 GB for 112
// maps of 512^2 in one set). Where that exceeds half the free memory the replay stays inactive
// and every texel is walked twice: scratch never makes a generation fail that fits without it.
#pragma once

#include <cstdint>

#include <nlohmann/json.hpp>

#include "cuda/buffer.h"
#include "engine/dsm/node_replay.h"
#include "strategies/storage/dsm_storage.h"

namespace dv {

// Scratch bytes a texel takes at the first generation's stripes (a chunk and its link per texel,
// a quarter more over the stripes; its kept record and lost slot): what a storage that bounds its
// scratch by generating in sets of faces plans with.
inline constexpr int64_t kReplayBytesPerTexel =
    (kReplayChunkNodes * int64_t(sizeof(DsmNode)) + 4) * 5 / 4 + int64_t(sizeof(KeptTexel)) + 4;

class NodeReplayScratch {
 public:
  // The replay over fresh buffers for c's texels: a generation's first (or only) set of faces.
  NodeReplay begin(const DsmGenerationContext& c);
  // The replay for the next set of faces of the same generation (c's texels): reads back what
  // the set before asked for and reuses its buffers where they are large enough.
  NodeReplay next(const DsmGenerationContext& c);
  // The replay begun, or an inactive one (every texel walked) when none is.
  NodeReplay replay() const { return replay_; }
  // Reads back what the last set asked for and frees the buffers; nothing when none began.
  void end();
  // replay_scratch_bytes (the most held at once) and replay_walked_texels of the last
  // generation.
  nlohmann::json figures() const;

 private:
  // The replay for c's texels, over the buffers held if they are large enough.
  NodeReplay claim(const DsmGenerationContext& c);
  // No scratch: every one of `texels` texels is walked twice.
  NodeReplay inactive(int64_t texels);
  void read_claims();
  void release();

  Buffer<DsmNode> nodes_;
  Buffer<int32_t> next_;
  Buffer<KeptTexel> kept_;
  Buffer<int32_t> lost_;
  Buffer<unsigned long long> counters_;
  NodeReplay replay_;
  int64_t largest_stripe_ = -1;  // the most chunks one stripe asked for in the last set
  int64_t walked_ = 0;           // texels it did not keep
  int64_t bytes_ = 0;            // bytes of the largest buffers of the last generation
};

}  // namespace dv
