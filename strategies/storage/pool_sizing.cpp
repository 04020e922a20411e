// The counting pass of the storages (see pool_sizing.h). Many texels share a total (all of
// them for texture3d), so a warp's lanes combine their counts before the atomic. Compiled by
// nvcc when CUDA is on.
#include "strategies/storage/pool_sizing.h"

#include "core/atomic.h"

namespace dv {

ParamSpec pool_sizing_param() {
  return choice_param("sizing", "counted", {"counted", "thesis"},
                      "counted: a counting pass sizes the pool to what the maps need (within "
                      "the limits); thesis: the paper's fixed reservation");
}

PoolSizing read_pool_sizing(const StrategyParams& params) {
  return params.string("sizing") == "thesis" ? PoolSizing::thesis : PoolSizing::counted;
}

const char* to_string(PoolSizing sizing) {
  return sizing == PoolSizing::thesis ? "thesis" : "counted";
}

std::vector<int32_t> count_nodes_per_group(const DsmGenerationContext& c,
                                           const NodeCountGroups& groups, int64_t group_count,
                                           NodeReplayScratch* scratch) {
  Buffer<int32_t> buffer(memory_of(c.backend), group_count, "dsm node counts per group");
  const View<int32_t> totals = buffer.view();
  const DsmGenerator g = c.generator;
  const float eps = c.eps;
  const NodeCountGroups by = groups;
  timed_pass(c, "count", [&] {
    const NodeReplay replay = scratch ? scratch->begin(c) : NodeReplay{};
    buffer.fill_zero();
    parallel_for(
        c.backend, "dsm_count_nodes", g.thread_count(), DV_KERNEL_LAMBDA(int64_t i) {
          DsmTexel t;
          if (!g.texel_of_thread(i, t)) return;
          const DsmTexelResult<KeepingSink<CountingNodeSink>> r =
              g.generate(t, eps, replay.sink<CountingNodeSink>(t));
          replay.keep(i, t, r);
          const int32_t nodes = r.record.nodes;
          int32_t* total = &totals[by.group_of(g, i, t.index)];
          if (by.maximum)
            atomic_max_combined(total, nodes);
          else
            atomic_add_combined(total, nodes);
        });
  });
  return buffer.to_vector();
}

double pool_units_wanted(const DsmGenerationContext& c, PoolSizing sizing, int64_t pool,
                         double thesis_units, const NodeCountGroups& groups, int64_t group_count,
                         int64_t per_unit, int64_t limit, NodeReplayScratch* scratch,
                         int64_t racers) {
  if (pool > 0) return double(pool);
  if (!counts_nodes(sizing, pool)) return thesis_units;
  double wanted = 0.0;
  for (int32_t nodes : count_nodes_per_group(c, groups, group_count, scratch))
    wanted += double(racers > 0 ? racing_units_worst(nodes, per_unit, limit, racers)
                                : units_needed(nodes, per_unit, limit));
  return wanted;
}

}  // namespace dv
