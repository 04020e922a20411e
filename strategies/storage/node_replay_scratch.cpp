// See node_replay_scratch.h.
#include "strategies/storage/node_replay_scratch.h"

#include <algorithm>
#include <limits>

#include "cuda/memory_check.h"

namespace dv {

NodeReplay NodeReplayScratch::begin(const DsmGenerationContext& c) {
  walked_ = 0;
  bytes_ = 0;
  return claim(c);
}

NodeReplay NodeReplayScratch::next(const DsmGenerationContext& c) {
  read_claims();
  return claim(c);
}

NodeReplay NodeReplayScratch::claim(const DsmGenerationContext& c) {
  const int64_t texels = c.generator.texel_count();
  // Chunk indices and the lost texels' threads are 32-bit: beyond that the replay stays inactive
  // and every texel is walked twice, as without it.
  const int64_t most_chunks = std::numeric_limits<int32_t>::max();
  if (texels == 0 || texels >= most_chunks || c.generator.thread_count() > most_chunks)
    return inactive(texels);
  const int64_t wanted = largest_stripe_ < 0 ? texels / 4 / kReplayStripes + 1
                                             : largest_stripe_ + largest_stripe_ / 8 + 1;
  const int64_t share = std::min(wanted, (most_chunks - texels) / kReplayStripes);
  const int64_t chunks = replay_chunks(texels, share);
  const Memory memory = memory_of(c.backend);
  if (nodes_.size() < chunks * kReplayChunkNodes || kept_.size() < texels ||
      nodes_.memory() != memory) {
    release();
    const int64_t bytes = chunks * (kReplayChunkNodes * int64_t(sizeof(DsmNode)) + 4) +
                          texels * int64_t(sizeof(KeptTexel) + 4) +
                          kReplayCounters * int64_t(sizeof(unsigned long long));
    if (bytes > free_memory_bytes(memory) / 2) return inactive(texels);  // room for the storage
    nodes_ = Buffer<DsmNode>(memory, chunks * kReplayChunkNodes, "dsm node replay chunks");
    next_ = Buffer<int32_t>(memory, chunks, "dsm node replay chunk links");
    kept_ = Buffer<KeptTexel>(memory, texels, "dsm node replay texels");
    lost_ = Buffer<int32_t>(memory, texels, "dsm node replay lost texels");
    counters_ = Buffer<unsigned long long>(memory, kReplayCounters, "dsm node replay counters");
    bytes_ = std::max<int64_t>(
        bytes_, nodes_.bytes() + next_.bytes() + kept_.bytes() + lost_.bytes() + counters_.bytes());
  }
  counters_.fill_zero();
  replay_ = {{nodes_.data(), chunks * kReplayChunkNodes},
             {next_.data(), chunks},
             {kept_.data(), texels},
             {lost_.data(), texels},
             counters_.view(),
             int32_t(share),
             c.first_texel};
  return replay_;
}

NodeReplay NodeReplayScratch::inactive(int64_t texels) {
  release();
  largest_stripe_ = -1;
  walked_ += texels;
  return replay_ = {};
}

void NodeReplayScratch::read_claims() {
  if (counters_.size() == 0) return;
  const ReplayClaims claims = replay_claims(counters_.to_vector());
  largest_stripe_ = claims.largest_stripe;
  walked_ += claims.walked;
}

void NodeReplayScratch::end() {
  read_claims();
  release();
  replay_ = {};
}

void NodeReplayScratch::release() {
  nodes_ = Buffer<DsmNode>();
  next_ = Buffer<int32_t>();
  kept_ = Buffer<KeptTexel>();
  lost_ = Buffer<int32_t>();
  counters_ = Buffer<unsigned long long>();
}

nlohmann::json NodeReplayScratch::figures() const {
  return {{"replay_scratch_bytes", bytes_}, {"replay_walked_texels", walked_}};
}

}  // namespace dv
