// Storage strategy `blocked` (see blocked_device.h). Parameters (table at the registration):
// tile = T texels per side, layers, pool = blocks of 8 layers x T^2 texels, pool_per_tile,
// sizing (strategies/storage/pool_sizing.h). The pool: `pool` when given; else counted sums over
// the tiles the blocks each needs for its deepest texel (at most layers / 8), and thesis reserves
// pool_per_tile per tile. A
// node beyond `layers` or with the pool exhausted ends the texel's function there (an overflow with
// the error reached, reported). Compiled by nvcc when CUDA is on.
#include <algorithm>
#include <limits>
#include <memory>

#include "core/error.h"
#include "cuda/ensure_buffer.h"
#include "strategies/storage/blocked_device.h"
#include "strategies/storage/dsm_storage.h"
#include "strategies/storage/node_replay_scratch.h"
#include "strategies/storage/pool_sizing.h"
#include "strategies/storage/replay_write.h"

namespace dv {

namespace {

template <bool kWalk>
void write_blocks(const DsmGenerationContext& c, NodeReplay replay, const BlockedSink& prototype,
                  View<int32_t> counts) {
  const DsmGenerator g = c.generator;
  const float eps = c.eps;
  const DsmRecordRange records = c.texel_records();
  for_replay_texels<kWalk>(
      c, replay, "dsm_blocked_write", DV_KERNEL_LAMBDA(int64_t, const DsmTexel& t) {
        BlockedSink sink = prototype;
        sink.tile = sink.layout.tile_of(t.index);
        sink.local = sink.layout.local_of(t.index);
        const DsmTexelResult<BlockedSink> r = replay.generate<kWalk>(g, t, eps, sink);
        counts[t.index] = r.sink.count;
        records[t.index] = r.record;
      });
}

class BlockedStorage final : public DsmStorage {
 public:
  explicit BlockedStorage(const StrategyParams& p)
      : params_(p),
        tile_(p.integer("tile")),
        layers_(p.integer("layers")),
        pool_per_tile_(p.number("pool_per_tile")),
        pool_(p.integer("pool")),
        sizing_(read_pool_sizing(p)) {}
  std::string name() const override { return "blocked"; }
  nlohmann::json params() const override { return params_.echo(); }

  void generate(const DsmGenerationContext& c) override {
    const DsmGenerator& g = c.generator;
    const Memory memory = memory_of(c.backend);
    const int res = g.resolution;
    layout_ = {tile_, (res + tile_ - 1) / tile_, res, layers_ / kBlockLayers, int64_t(res) * res};
    tiles_ = g.faces.size * int64_t(layout_.tiles_per_side) * layout_.tiles_per_side;
    const int64_t block_entries = int64_t(kBlockLayers) * tile_ * tile_;
    const double wanted = pool_units_wanted(c, sizing_, pool_, pool_per_tile_ * double(tiles_),
                                            {NodeCountGroups::tile, true, layout_}, tiles_,
                                            kBlockLayers, layout_.blocks_per_tile, &scratch_);
    capacity_ = int32_t(std::min(wanted, 2147483647.0));
    ensure_buffer(indirection_, memory, tiles_ * layout_.blocks_per_tile, "dsm block indirection");
    ensure_buffer(used_, memory, 1, "dsm blocks used");
    ensure_buffer(pool_nodes_, memory, int64_t(capacity_) * block_entries, "dsm block pool");
    ensure_buffer(counts_, memory, g.texel_count(), "dsm block layer counts");
    const BlockedSink prototype{
        layout_, indirection_.view(), used_.view(), pool_nodes_.view(), capacity_, 0, 0};
    timed_pass(c, "write", [&] {
      indirection_.fill_zero();
      used_.fill_zero();
      const NodeReplay replay = scratch_.replay();
      run_replay_write(
          replay, [&]<bool kWalk>() { write_blocks<kWalk>(c, replay, prototype, counts_.view()); });
    });
    scratch_.end();
    taken_ = used_.to_vector()[0];
  }

  DsmReader reader() const override {
    return DsmReader(BlockedReader{layout_, indirection_.const_view(), pool_nodes_.const_view(),
                                   counts_.const_view()});
  }
  int64_t bytes_allocated() const override {
    return indirection_.bytes() + used_.bytes() + pool_nodes_.bytes() + counts_.bytes();
  }
  bool keeps_error_bound() const override { return true; }
  int64_t bytes_per_node() const override { return sizeof(DsmNode); }
  nlohmann::json own_figures() const override {
    const int64_t allocated = std::min<int64_t>(taken_, capacity_);
    const int64_t block_bytes = int64_t(kBlockLayers) * tile_ * tile_ * int64_t(sizeof(DsmNode));
    nlohmann::json figures = {
        {"tiles", tiles_},
        {"pool_blocks", capacity_},
        {"blocks_allocated", allocated},
        {"pool_exhausted", taken_ > capacity_},
        {"block_bytes", block_bytes},
        {"blocks_per_tile", tiles_ ? double(allocated) / double(tiles_) : 0.0},
        {"bytes_in_blocks", allocated * block_bytes}};
    figures.update(scratch_.figures());
    return figures;
  }

 private:
  StrategyParams params_;
  int tile_, layers_;
  double pool_per_tile_;
  int32_t pool_;
  PoolSizing sizing_;
  int32_t capacity_ = 0;
  BlockedLayout layout_{};
  int64_t tiles_ = 0, taken_ = 0;
  Buffer<int32_t> indirection_, used_, counts_;
  Buffer<DsmNode> pool_nodes_;
  NodeReplayScratch scratch_;
};

}  // namespace

void register_blocked_storage(Registry<DsmStorage>& registry) {
  registry.add(
      "blocked", "Hadwiger 2006 3.4: tiles, blocks of 8 layers on demand, indirection per tile",
      {integer_param("tile", 8, 1, 256, "texels per tile side"),
       multiple_param("layers", 256, kBlockLayers, kBlockLayers, 65536, "most layers per texel"),
       integer_param("pool", 0, 0, std::numeric_limits<int32_t>::max(),
                     "blocks in the pool (8 layers x tile^2 texels); 0: by sizing"),
       positive_param("pool_per_tile", 8.0, "blocks reserved per tile by sizing=thesis"),
       pool_sizing_param()},
      [](const StrategyParams& p) { return std::make_unique<BlockedStorage>(p); });
}

}  // namespace dv
