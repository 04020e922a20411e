// Storage strategy `compact` (see compact_device.h): counting pass (which keeps the nodes for
// the packing pass, engine/dsm/node_replay.h), exclusive scan, packing pass. Compiled by nvcc when
// CUDA is on.
#include <memory>

#include "cuda/ensure_buffer.h"
#include "cuda/scan.h"
#include "strategies/storage/compact_device.h"
#include "strategies/storage/dsm_storage.h"
#include "strategies/storage/node_replay_scratch.h"
#include "strategies/storage/replay_write.h"

namespace dv {

namespace {

void count_nodes(const DsmGenerationContext& c, NodeReplay replay, View<int64_t> counts) {
  const DsmGenerator g = c.generator;
  const float eps = c.eps;
  parallel_for(
      c.backend, "dsm_compact_count", g.thread_count(), DV_KERNEL_LAMBDA(int64_t i) {
        DsmTexel t;
        if (!g.texel_of_thread(i, t)) return;
        const DsmTexelResult<KeepingSink<CountingNodeSink>> r =
            g.generate(t, eps, replay.sink<CountingNodeSink>(t));
        counts[t.index] = r.record.nodes;
        replay.keep(i, t, r);
      });
}

template <bool kWalk>
void write_nodes(const DsmGenerationContext& c, NodeReplay replay, View<const int64_t> offsets,
                 View<DsmNode> nodes) {
  const DsmGenerator g = c.generator;
  const float eps = c.eps;
  const View<DsmTexelRecord> records = c.records;
  for_replay_texels<kWalk>(
      c, replay, "dsm_compact_write", DV_KERNEL_LAMBDA(int64_t, const DsmTexel& t) {
        const int64_t begin = offsets[t.index];
        const CompactSink sink{nodes.data + begin, offsets[t.index + 1] - begin};
        records[t.index] = replay.generate<kWalk>(g, t, eps, sink).record;
      });
}

class CompactStorage final : public DsmStorage {
 public:
  std::string name() const override { return "compact"; }
  nlohmann::json params() const override { return nlohmann::json::object(); }

  void generate(const DsmGenerationContext& c) override {
    const int64_t texels = c.generator.texel_count();
    ensure_buffer(offsets_, memory_of(c.backend), texels + 1, "dsm compact offsets");
    timed_pass(c, "count", [&] {
      offsets_.fill_zero();
      count_nodes(c, scratch_.begin(c), offsets_.view());
    });
    int64_t total = 0;
    timed_pass(c, "scan", [&] { total = exclusive_scan_in_place(c.backend, offsets_.view()); });
    ensure_buffer(nodes_, memory_of(c.backend), total, "dsm compact nodes");
    timed_pass(c, "write", [&] {
      const NodeReplay replay = scratch_.replay();
      run_replay_write(replay, [&]<bool kWalk>() {
        write_nodes<kWalk>(c, replay, offsets_.const_view(), nodes_.view());
      });
    });
    scratch_.end();
  }

  DsmReader reader() const override {
    return DsmReader(CompactReader{offsets_.const_view(), nodes_.const_view()});
  }
  int64_t bytes_allocated() const override { return offsets_.bytes() + nodes_.bytes(); }
  bool keeps_error_bound() const override { return true; }
  int64_t bytes_per_node() const override { return sizeof(DsmNode); }
  DsmHostNodes host_nodes() const override { return {offsets_.to_vector(), nodes_.to_vector()}; }
  nlohmann::json own_figures() const override { return scratch_.figures(); }

 private:
  Buffer<int64_t> offsets_;
  Buffer<DsmNode> nodes_;
  NodeReplayScratch scratch_;
};

}  // namespace

void register_compact_storage(Registry<DsmStorage>& registry) {
  registry.add("compact",
               "ours: count, scan, pack into one exact-size array; zero waste, binary search", {},
               [](const StrategyParams&) { return std::make_unique<CompactStorage>(); });
}

}  // namespace dv
