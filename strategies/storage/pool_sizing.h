// How the pooled storages (texture3d, chunked, blocked) size their pools. `counted` (default):
// a counting pass first (the compact storage's: every texel's function compressed into a sink
// that counts, and for chunked and blocked keeps the nodes for the write pass to replay,
// engine/dsm/node_replay.h), reduced per group of texels that shares pool space (the whole atlas, a
// generation block, a tile), and the pool sized to exactly what the maps need, never beyond the
// strategy's limits (layers, chunks per block, an explicit pool), so those limits still
// overflow and are reported. `thesis`: the fixed formulas of the papers (layers x texels,
// chunks or blocks per tile), which reserve the same bytes whatever the scene.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/hd.h"
#include "core/registry.h"
#include "strategies/storage/blocked_device.h"
#include "strategies/storage/dsm_storage.h"
#include "strategies/storage/node_replay_scratch.h"

namespace dv {

enum class PoolSizing { counted, thesis };

// The `sizing` parameter of the pooled storages, and reading it.
ParamSpec pool_sizing_param();
PoolSizing read_pool_sizing(const StrategyParams& params);
const char* to_string(PoolSizing sizing);

// Which texels share a total in the counting pass, and how their node counts combine.
struct NodeCountGroups {
  enum Kind : int32_t { generation_block, tile, all } kind;
  bool maximum;           // largest count of the group instead of the sum
  BlockedLayout tiles{};  // for kind == tile

  DV_HD int64_t group_of(const DsmGenerator& g, int64_t thread, int64_t texel) const {
    if (kind == generation_block) return g.block_of_thread(thread);
    if (kind == tile) return tiles.tile_of(texel);
    return 0;
  }
};

// Whether the pool is sized by a counting pass: counted sizing and no explicit pool.
inline bool counts_nodes(PoolSizing sizing, int64_t pool) {
  return pool <= 0 && sizing == PoolSizing::counted;
}

// The counting pass over every texel of c.generator (at c.eps), reduced per group: the totals
// in host memory, `group_count` of them. Timed as pass "count". Keeps the nodes for the write
// pass in a replay begun in `scratch` when one is given (engine/dsm/node_replay.h).
std::vector<int32_t> count_nodes_per_group(const DsmGenerationContext& c,
                                           const NodeCountGroups& groups, int64_t group_count,
                                           NodeReplayScratch* scratch = nullptr);

// Pool units (chunks, blocks) a group needs for `nodes` nodes at `per_unit` nodes a unit, at
// most `limit` of them (more would be refused anyway).
inline int64_t units_needed(int64_t nodes, int64_t per_unit, int64_t limit) {
  const int64_t units = (nodes + per_unit - 1) / per_unit;
  return units < limit ? units : limit;
}

// The most pool units a group's racing allocation (claim_racing, slot_claim.h) can take for
// `nodes` nodes at `per_unit` nodes a unit, at most `limit` units used, among `racers` threads:
// each node's claim takes at most one unit, and a thread that has claimed a slot sees it taken
// from then on, so a slot costs at most min(nodes written in it, racers) units. A pool of the sum
// over the groups cannot run out whatever the schedule, and still lets the race waste as it does.
inline int64_t racing_units_worst(int64_t nodes, int64_t per_unit, int64_t limit, int64_t racers) {
  const int64_t per_full = per_unit < racers ? per_unit : racers;
  const int64_t full = nodes / per_unit, rest = nodes % per_unit;
  if (full >= limit) return limit * per_full;
  return full * per_full + (rest < racers ? rest : racers);
}

// How many pool units (chunks, blocks) to reserve: an explicit `pool` (> 0) as given; else with
// counted sizing the sum over the groups of what each group's count needs (units_needed at
// `per_unit` nodes a unit, at most `limit` a group, or with `racers` > 0 racing_units_worst
// among that many threads; the counting pass runs and keeps the nodes in `scratch`); else
// `thesis_units`, the papers' formula.
double pool_units_wanted(const DsmGenerationContext& c, PoolSizing sizing, int64_t pool,
                         double thesis_units, const NodeCountGroups& groups, int64_t group_count,
                         int64_t per_unit, int64_t limit, NodeReplayScratch* scratch = nullptr,
                         int64_t racers = 0);

}  // namespace dv
