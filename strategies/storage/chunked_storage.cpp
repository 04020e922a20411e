// Storage strategy `chunked` (see chunked_device.h). Parameters (table at the registration):
// alloc, chunk = L_C layers per chunk, block_chunks = C_B, pool = C_max chunks, pool_per_block,
// sizing (strategies/storage/pool_sizing.h). The pool: `pool` when given; else counted sums over
// the 8x8 blocks the chunks each needs for its nodes (at most C_B; with alloc=thesis the most
// its race can take, racing_units_worst), and thesis reserves pool_per_block per block.
// `thesis` allocates as Knecht's
// Algorithm 4.1 (threads of a block race, losers' chunks are wasted: measured, reported);
// `aggregated` claims each chunk once with a pending state, so a block wastes at most the
// unused tail of its last chunk. A refused node (block at C_B, or pool exhausted) ends the
// texel's function there: counted as an overflow with the error reached, reported per
// generation, never written out of bounds. Compiled by nvcc when CUDA is on.
#include <algorithm>
#include <limits>
#include <memory>

#include "core/error.h"
#include "cuda/ensure_buffer.h"
#include "strategies/storage/chunked_device.h"
#include "strategies/storage/dsm_storage.h"
#include "strategies/storage/node_replay_scratch.h"
#include "strategies/storage/pool_sizing.h"
#include "strategies/storage/replay_write.h"

namespace dv {

namespace {

template <bool kWalk>
void write_chunks(const DsmGenerationContext& c, NodeReplay replay, const ChunkPool& pool) {
  const DsmGenerator g = c.generator;
  const float eps = c.eps;
  const DsmRecordRange records = c.texel_records();
  for_replay_texels<kWalk>(
      c, replay, "dsm_chunked_write", DV_KERNEL_LAMBDA(int64_t i, const DsmTexel& t) {
        const ChunkedSink sink{pool, g.block_of_thread(i), t.index};
        records[t.index] = replay.generate<kWalk>(g, t, eps, sink).record;
      });
}

// Packs the allocated part of the pool into one entry per layer (the thesis's float4 texture).
void relayout(Backend backend, const ChunkPool& pool, View<ChunkEntry> entries) {
  parallel_for(
      backend, "dsm_chunked_relayout", entries.size, DV_KERNEL_LAMBDA(int64_t e) {
        entries[e] = {pool.depth[e], pool.visibility[e], pool.next_chunk[e], pool.next_layer[e]};
      });
}

class ChunkedStorage final : public DsmStorage {
 public:
  explicit ChunkedStorage(const StrategyParams& p)
      : params_(p),
        alloc_(p.string("alloc")),
        chunk_layers_(p.integer("chunk")),
        block_limit_(p.integer("block_chunks")),
        pool_per_block_(p.number("pool_per_block")),
        pool_(p.integer("pool")),
        sizing_(read_pool_sizing(p)) {}
  std::string name() const override { return "chunked"; }
  nlohmann::json params() const override { return params_.echo(); }

  void generate(const DsmGenerationContext& c) override {
    blocks_ = c.generator.thread_count() / (kDsmBlockSide * kDsmBlockSide);
    // The racing allocation (alloc=thesis) loses chunks to the race, so a counted pool holds
    // the race's worst case (racing_units_worst: at most one chunk per node, per thread and
    // slot): one write pass, no node refused whatever the schedule, and the waste is what the
    // race took beyond the used chunks. (Retrying with a larger pool when the race had exhausted
    // it timed several write passes; growing only to what the race took left the seeds' runs of
    // 2026-12-01 16,549 refused texels short at 512^2.) Anything still refused (a fixed pool,
    // the block limit C_B, the 32-bit limit) is reported as overflowed texels.
    const double wanted = pool_units_wanted(
        c, sizing_, pool_, pool_per_block_ * double(blocks_),
        {NodeCountGroups::generation_block, false}, blocks_, chunk_layers_, block_limit_, &scratch_,
        alloc_ == "thesis" ? int64_t(kDsmBlockSide) * kDsmBlockSide : 0);
    write_pool(c, wanted);
    scratch_.end();
  }

  DsmReader reader() const override {
    return DsmReader(ChunkedReader{entries_.const_view(), first_.const_view(), chunk_layers_});
  }
  int64_t bytes_allocated() const override {
    return depth_.bytes() + visibility_.bytes() + next_chunk_.bytes() + next_layer_.bytes() +
           block_layers_.bytes() + block_chunks_.bytes() + counters_.bytes() + first_.bytes() +
           entries_.bytes();
  }
  bool keeps_error_bound() const override { return true; }
  int64_t bytes_per_node() const override { return sizeof(ChunkEntry); }
  nlohmann::json own_figures() const override {
    const int64_t allocated = std::min<int64_t>(taken_, capacity_);
    nlohmann::json figures = {
        {"chunk_bytes", int64_t(chunk_layers_) * int64_t(sizeof(ChunkEntry))},
        {"pool_chunks", capacity_},
        {"chunks_allocated", allocated},
        {"chunks_used", used_},
        {"chunks_wasted", allocated - used_},
        {"pool_exhausted", taken_ > capacity_},
        {"refused_nodes", refused_},
        {"blocks", blocks_},
        {"used_chunks_per_block", blocks_ ? double(used_) / double(blocks_) : 0.0},
        {"wasted_chunks_per_block", blocks_ ? double(allocated - used_) / double(blocks_) : 0.0},
        {"lookup_bytes", entries_.bytes() + first_.bytes()}};
    figures.update(scratch_.figures());
    return figures;
  }

 private:
  // The most chunks a pool may hold: their entries are indexed by 32-bit ints.
  double max_pool_chunks() const { return double((int64_t(1) << 31) - 1) / chunk_layers_; }

  // Writes every texel's nodes into a pool of `wanted` chunks (at most max_pool_chunks) and
  // packs the allocated chunks.
  void write_pool(const DsmGenerationContext& c, double wanted) {
    const DsmGenerator& g = c.generator;
    const Memory memory = memory_of(c.backend);
    capacity_ = int32_t(std::min(wanted, max_pool_chunks()));
    const int64_t pool_entries = int64_t(capacity_) * chunk_layers_;
    ensure_buffer(depth_, memory, pool_entries, "dsm chunk depths");
    ensure_buffer(visibility_, memory, pool_entries, "dsm chunk visibilities");
    ensure_buffer(next_chunk_, memory, pool_entries, "dsm chunk next chunks");
    ensure_buffer(next_layer_, memory, pool_entries, "dsm chunk next layers");
    ensure_buffer(block_layers_, memory, blocks_, "dsm block layer counters");
    ensure_buffer(block_chunks_, memory, blocks_ * block_limit_, "dsm block chunk table");
    ensure_buffer(counters_, memory, 2, "dsm chunk counters");
    ensure_buffer(first_, memory, g.texel_count(), "dsm chunk lookup table");
    const ChunkPool pool{depth_.view(),         visibility_.view(),
                         next_chunk_.view(),    next_layer_.view(),
                         block_layers_.view(),  block_chunks_.view(),
                         {counters_.data(), 1}, {counters_.data() + 1, 1},
                         first_.view(),         chunk_layers_,
                         block_limit_,          capacity_,
                         alloc_ == "thesis"};
    timed_pass(c, "write", [&] {
      block_layers_.fill_zero();
      block_chunks_.fill_zero();
      counters_.fill_zero();
      first_.fill_zero();
      const NodeReplay replay = scratch_.replay();
      run_replay_write(replay, [&]<bool kWalk>() { write_chunks<kWalk>(c, replay, pool); });
    });
    const std::vector<int32_t> counters = counters_.to_vector();
    taken_ = counters[0];
    refused_ = counters[1];
    const int64_t allocated = std::min<int64_t>(taken_, capacity_);
    timed_pass(c, "relayout", [&] {
      ensure_buffer(entries_, memory, allocated * chunk_layers_, "dsm chunk texture");
      relayout(c.backend, pool, entries_.view());
    });
    used_ = 0;
    for (int32_t slot : block_chunks_.to_vector()) used_ += slot > 0;
  }

  StrategyParams params_;
  std::string alloc_;
  int32_t chunk_layers_, block_limit_;
  double pool_per_block_;
  int32_t pool_;
  PoolSizing sizing_;
  int32_t capacity_ = 0;
  int64_t blocks_ = 0, taken_ = 0, refused_ = 0, used_ = 0;
  Buffer<float> depth_, visibility_;
  Buffer<int32_t> next_chunk_, next_layer_, block_layers_, block_chunks_, counters_;
  Buffer<ChunkFirst> first_;
  Buffer<ChunkEntry> entries_;
  NodeReplayScratch scratch_;
};

}  // namespace

void register_chunked_storage(Registry<DsmStorage>& registry) {
  registry.add(
      "chunked", "Knecht 2011 4.2.2: chunks from a global pool per 8x8 block, linked lists",
      {choice_param("alloc", "aggregated", {"aggregated", "thesis"},
                    "thesis: Knecht's Algorithm 4.1 (a block's threads race, losers' "
                    "chunks wasted); aggregated: each chunk claimed once"),
       integer_param("chunk", 64, 1, 1024, "layers per chunk (L_C)"),
       integer_param("block_chunks", 64, 1, 65536, "most chunks per 8x8 block (C_B)"),
       integer_param("pool", 0, 0, std::numeric_limits<int32_t>::max(),
                     "chunks in the pool (C_max); 0: by sizing"),
       positive_param("pool_per_block", 32.0, "chunks reserved per block by sizing=thesis"),
       pool_sizing_param()},
      [](const StrategyParams& p) { return std::make_unique<ChunkedStorage>(p); });
}

}  // namespace dv
