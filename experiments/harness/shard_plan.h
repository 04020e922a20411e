// Which shard runs which item: items are balanced by expected cost, not by count (LPT: the
// costliest item first, each to the least-loaded shard; ties by item index and shard number, so
// every worker and the merge compute the same assignment). Costs come from a previous run's
// timings (rows.csv of a whole or merged run of the same suite file) or, without one, from a
// documented estimate (docs/scale-out.md). Each shard's meta.json stores the cost source and a
// hash of the assignment; merge refuses shards whose assignments differ.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "experiments/harness/suite_file.h"

namespace dv {

// Expected cost of one item in arbitrary units: shadow: width x height (+ 50 per probe point)
// + res^2 of the map, x4 for the reference (oracle per pixel); voxelize: the voxel count.
double estimated_cost(const RunItem& item);

struct ItemCosts {
  std::string source;              // "estimate" or the previous run's folder
  std::map<int, double> by_index;  // item index -> cost
};

// `costs`: "" (the newest earlier whole or merged run of the same suite file under
// OUT/<suite>/, else the estimate), "estimate", or a result folder (InputError when it is not
// one of this suite file).
ItemCosts item_costs(const std::vector<RunItem>& items, const Suite& suite,
                     const std::string& costs, const std::string& out);

struct ShardPlan {
  std::vector<int> shard_of;  // per position in `items`: 1-based shard
  std::vector<double> load;   // per shard (0-based): summed cost
  std::string hash;           // FNV-1a of "index:shard" pairs
};
ShardPlan plan_shards(const std::vector<RunItem>& items, const ItemCosts& costs, int count);

// The items of shard I/N under `plan`, in order.
std::vector<RunItem> shard_items(const std::vector<RunItem>& items, const ShardPlan& plan,
                                 const Shard& shard);

}  // namespace dv
