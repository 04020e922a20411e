// Storage strategy `compact` (see compact_device.h): counting pass (which keeps the nodes for
// the packing pass, engine/dsm/node_replay.h), the two-level scan of the counts, packing pass.
// Compiled by nvcc when CUDA is on.
#include <cstdint>
#include <memory>
#include <string>

#include "core/atomic.h"
#include "core/error.h"
#include "cuda/ensure_buffer.h"
#include "cuda/execute.h"
#include "cuda/scan.h"
#include "strategies/storage/compact_device.h"
#include "strategies/storage/dsm_storage.h"
#include "strategies/storage/node_replay_scratch.h"
#include "strategies/storage/replay_write.h"

namespace dv {

namespace {

// Two blocks of 256 threads per SM (128 registers, parallel_for_bounded): the counting walk
// generates faster than at the occupancy calculator's 255 registers
// (results/perf/2026-12-06-register-budget).
void count_nodes(const DsmGenerationContext& c, NodeReplay replay, View<uint32_t> counts) {
  const DsmGenerator g = c.generator;
  const float eps = c.eps;
  parallel_for_bounded<2>(
      c.backend, "dsm_compact_count", g.thread_count(), DV_KERNEL_LAMBDA(int64_t i) {
        DsmTexel t;
        if (!g.texel_of_thread(i, t)) return;
        const DsmTexelResult<KeepingSink<CountingNodeSink>> r =
            g.generate(t, eps, replay.sink<CountingNodeSink>(t));
        counts[t.index] = uint32_t(r.record.nodes);
        replay.keep(i, t, r);
      });
}

// Turns each group's counts into starts within the group and leaves the group's total in
// `group_starts` for the scan; the largest total above 2^32 - 1 (the starts within a group are
// 32-bit) goes to `largest`.
void start_within_groups(Backend backend, View<uint32_t> counts, View<int64_t> group_starts,
                         View<unsigned long long> largest) {
  parallel_for(
      backend, "dsm_compact_group_starts", group_starts.size, DV_KERNEL_LAMBDA(int64_t g) {
        const int64_t first = g * kCompactGroupTexels;
        const int64_t end = min_value(first + kCompactGroupTexels, counts.size);
        unsigned long long sum = 0;
        for (int64_t t = first; t < end; ++t) {
          const uint32_t n = counts[t];
          counts[t] = uint32_t(sum);
          sum += n;
        }
        group_starts[g] = int64_t(sum);
        if (sum > 0xffffffffull) atomic_max(largest.data, sum);
      });
}

template <bool kWalk>
void write_nodes(const DsmGenerationContext& c, NodeReplay replay, CompactStarts starts,
                 View<DsmNode> nodes) {
  const DsmGenerator g = c.generator;
  const float eps = c.eps;
  const View<DsmTexelRecord> records = c.records;
  for_replay_texels<kWalk>(
      c, replay, "dsm_compact_write", DV_KERNEL_LAMBDA(int64_t, const DsmTexel& t) {
        const int64_t begin = starts.start(t.index);
        const CompactSink sink{nodes.data + begin, starts.start(t.index + 1) - begin};
        records[t.index] = replay.generate<kWalk>(g, t, eps, sink).record;
      });
}

class CompactStorage final : public DsmStorage {
 public:
  std::string name() const override { return "compact"; }
  nlohmann::json params() const override { return nlohmann::json::object(); }

  void generate(const DsmGenerationContext& c) override {
    const int64_t texels = c.generator.texel_count();
    const Memory memory = memory_of(c.backend);
    ensure_buffer(local_starts_, memory, texels + 1, "dsm compact starts within groups");
    ensure_buffer(group_starts_, memory, compact_groups(texels), "dsm compact group starts");
    ensure_buffer(largest_group_, memory, 1, "dsm compact largest group");
    timed_pass(c, "count", [&] {
      local_starts_.fill_zero();
      count_nodes(c, scratch_.begin(c), local_starts_.view());
    });
    int64_t total = 0;
    timed_pass(c, "scan", [&] {
      largest_group_.fill_zero();
      start_within_groups(c.backend, local_starts_.view(), group_starts_.view(),
                          largest_group_.view());
      total = exclusive_scan_in_place(c.backend, group_starts_.view());
    });
    const unsigned long long largest = largest_group_.to_vector()[0];
    if (largest > 0) {
      scratch_.end();
      throw Error("dsm storage 'compact': " + std::to_string(largest) + " nodes in one group of " +
                  std::to_string(kCompactGroupTexels) +
                  " texels, more than its 32-bit starts hold (4294967295)");
    }
    ensure_buffer(nodes_, memory, total, "dsm compact nodes");
    timed_pass(c, "write", [&] {
      const NodeReplay replay = scratch_.replay();
      run_replay_write(
          replay, [&]<bool kWalk>() { write_nodes<kWalk>(c, replay, starts(), nodes_.view()); });
    });
    scratch_.end();
  }

  DsmReader reader() const override {
    return DsmReader(CompactReader{starts(), nodes_.const_view()});
  }
  int64_t bytes_allocated() const override {
    return group_starts_.bytes() + local_starts_.bytes() + nodes_.bytes();
  }
  bool keeps_error_bound() const override { return true; }
  int64_t bytes_per_node() const override { return sizeof(DsmNode); }
  DsmHostNodes host_nodes() const override {
    const std::vector<int64_t> groups = group_starts_.to_vector();
    const std::vector<uint32_t> local = local_starts_.to_vector();
    const CompactStarts host{{groups.data(), int64_t(groups.size())},
                             {local.data(), int64_t(local.size())}};
    std::vector<int64_t> offsets(local.size());
    for (size_t t = 0; t < offsets.size(); ++t) offsets[t] = host.start(int64_t(t));
    return {offsets, nodes_.to_vector()};
  }
  nlohmann::json own_figures() const override { return scratch_.figures(); }

 private:
  CompactStarts starts() const { return {group_starts_.const_view(), local_starts_.const_view()}; }

  Buffer<int64_t> group_starts_;
  Buffer<uint32_t> local_starts_;
  Buffer<unsigned long long> largest_group_;
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
