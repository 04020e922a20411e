// Storage strategy `avsm` (Salvi et al. 2010, see avsm_device.h): N nodes per texel, 8 N bytes
// (parameter `nodes`). A storage strategy rather than a shadow method because
// it changes only what a texel keeps of the visibility function the DSM walk produces: the
// walk, the light faces, the receiver bias, the filter and the lookups' clamp rules stay those
// of `dsm`, so the comparison with the papers' storages isolates the representation. The walk
// samples constant media for the shared eps; the function is passed on exactly (compressor
// eps 0), so N is the only approximation. One pass; the shared figures count a texel whose
// function needed more than N nodes as overflowed (flag kDsmNodesMerged) with its error bound.
// Compiled by nvcc when CUDA is on.
#include <memory>

#include "core/error.h"
#include "cuda/ensure_buffer.h"
#include "strategies/storage/avsm_device.h"
#include "strategies/storage/dsm_storage.h"

namespace dv {

namespace {

void write_avsm_nodes(const DsmGenerationContext& c, int capacity, View<DsmNode> nodes) {
  const DsmGenerator g = c.generator;
  const float sample_eps = c.eps;
  const DsmRecordRange records = c.texel_records();
  parallel_for(
      c.backend, "dsm_avsm_write", g.thread_count(), DV_KERNEL_LAMBDA(int64_t i) {
        DsmTexel t;
        if (!g.texel_of_thread(i, t)) return;
        AvsmSink empty;
        empty.capacity = capacity;
        const DsmTexelResult<AvsmSink> r = g.generate(t, 0.0f, empty, sample_eps);
        r.sink.store(nodes.data + t.index * capacity);
        DsmTexelRecord record = r.record;
        record.stored = r.sink.count;
        record.error = min_value(record.error + r.sink.dropped_change, 1.0f);
        if (r.sink.dropped > 0) record.flags |= kDsmNodesMerged;
        records[t.index] = record;
      });
}

class AvsmStorage final : public DsmStorage {
 public:
  explicit AvsmStorage(const StrategyParams& p) : params_(p), capacity_(p.integer("nodes")) {}
  std::string name() const override { return "avsm"; }
  nlohmann::json params() const override { return params_.echo(); }

  void generate(const DsmGenerationContext& c) override {
    ensure_buffer(nodes_, memory_of(c.backend), c.generator.texel_count() * capacity_,
                  "dsm avsm nodes");
    timed_pass(c, "write", [&] { write_avsm_nodes(c, capacity_, nodes_.view()); });
  }

  DsmReader reader() const override {
    return DsmReader(AvsmReader{nodes_.const_view(), capacity_});
  }
  int64_t bytes_allocated() const override { return nodes_.bytes(); }
  // A fixed number of nodes: its error is measured against the oracle, not bounded by eps.
  bool keeps_error_bound() const override { return false; }
  int64_t bytes_per_node() const override { return sizeof(DsmNode); }
  nlohmann::json own_figures() const override {
    return {{"nodes_per_texel", capacity_},
            {"bytes_per_texel", capacity_ * int64_t(sizeof(DsmNode))}};
  }

 private:
  StrategyParams params_;
  int capacity_;
  Buffer<DsmNode> nodes_;
};

}  // namespace

void register_avsm_storage(Registry<DsmStorage>& registry) {
  registry.add("avsm",
               "Salvi et al. 2010 adaptive volumetric shadow maps: N nodes per texel (8 N bytes), "
               "streaming insertion dropping the least-area node; error unbounded",
               {integer_param("nodes", 8, 2, kAvsmMaxNodes, "nodes per texel (8 bytes each)")},
               [](const StrategyParams& p) { return std::make_unique<AvsmStorage>(p); });
}

}  // namespace dv
