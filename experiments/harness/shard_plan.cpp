// Cost-balanced shard assignment (shard_plan.h).
#include "experiments/harness/shard_plan.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <numeric>

#include "core/error.h"
#include "core/json_reader.h"
#include "experiments/harness/rows.h"

namespace dv {

namespace fs = std::filesystem;

namespace {

// "128x128x64" or "64" -> voxel count.
double voxel_count(const std::string& res) {
  double count = 1.0;
  int dims = 0;
  size_t at = 0;
  while (at <= res.size()) {
    const size_t x = std::min(res.find('x', at), res.size());
    count *= std::max(1.0, std::atof(res.substr(at, x - at).c_str()));
    ++dims;
    at = x + 1;
  }
  return dims == 1 ? count * count * count : count;
}

double setting(const std::map<std::string, std::string>& map, const std::string& key,
               double fallback) {
  const auto it = map.find(key);
  return it == map.end() ? fallback : std::atof(it->second.c_str());
}

// A whole or merged run of `suite`'s file that ended: meta.json with its hash, one shard and
// (folders that resume) the state "finished".
bool is_whole_run_of(const fs::path& dir, const Suite& suite) {
  const fs::path meta_path = dir / "meta.json";
  if (!fs::is_regular_file(meta_path) || !fs::is_regular_file(dir / "rows.csv")) return false;
  const Json meta = parse_json_file(meta_path.string());
  return meta.value("suite_hash", "") == suite.hash && meta.contains("shard") &&
         meta["shard"].value("count", 0) == 1 && meta.value("state", "finished") == "finished";
}

// Per item: the sum of its median timings (ms).
std::map<int, double> timings(const fs::path& dir) {
  std::map<int, double> ms;
  for (const Row& r : read_rows_csv((dir / "rows.csv").string()))
    if (r.unit == "ms" && r.stat == "median") ms[r.item] += r.value;
  return ms;
}

}  // namespace

double estimated_cost(const RunItem& item) {
  if (item.kind == "voxelize")
    return voxel_count(item.settings.count("res") ? item.settings.at("res") : "64");
  const double res = setting(item.params, "res", 256.0);
  const double pixels =
      setting(item.settings, "width", 320.0) * setting(item.settings, "height", 200.0);
  const double work = pixels + 50.0 * setting(item.settings, "probe_points", 400.0) + res * res;
  return item.strategy == "reference" ? 4.0 * work : work;
}

ItemCosts item_costs(const std::vector<RunItem>& items, const Suite& suite,
                     const std::string& costs, const std::string& out) {
  ItemCosts result{"estimate", {}};
  fs::path previous;
  if (costs.empty()) {
    std::error_code ec;
    const fs::path parent = fs::path(out) / suite.name;
    std::vector<fs::path> runs;
    if (fs::is_directory(parent, ec))
      for (const auto& entry : fs::directory_iterator(parent, ec))
        if (is_whole_run_of(entry.path(), suite)) runs.push_back(entry.path());
    std::sort(runs.begin(), runs.end());  // folder names begin with the UTC time
    if (!runs.empty()) previous = runs.back();
  } else if (costs != "estimate") {
    if (!is_whole_run_of(costs, suite))
      throw InputError(costs, "--costs: not a whole or merged result folder of suite file " +
                                  suite.file + " (hash " + suite.hash + ")");
    previous = costs;
  }
  std::map<int, double> ms;
  if (!previous.empty()) ms = timings(previous);
  if (!ms.empty()) result.source = previous.string();
  // Items without timings (failed, skipped) cost the mean of the timed ones.
  double mean = 0.0;
  for (const auto& [index, value] : ms) mean += value / double(ms.size());
  for (const RunItem& item : items)
    result.by_index[item.index] =
        ms.empty() ? estimated_cost(item) : (ms.count(item.index) ? ms[item.index] : mean);
  return result;
}

ShardPlan plan_shards(const std::vector<RunItem>& items, const ItemCosts& costs, int count) {
  std::vector<size_t> order(items.size());
  std::iota(order.begin(), order.end(), size_t(0));
  const auto cost = [&](size_t k) { return costs.by_index.at(items[k].index); };
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return cost(a) > cost(b); });
  ShardPlan plan;
  plan.shard_of.assign(items.size(), 1);
  plan.load.assign(size_t(count), 0.0);
  for (size_t k : order) {
    const size_t least =
        size_t(std::min_element(plan.load.begin(), plan.load.end()) - plan.load.begin());
    plan.shard_of[k] = int(least) + 1;
    plan.load[least] += cost(k);
  }
  std::string pairs;
  for (size_t k = 0; k < items.size(); ++k)
    pairs += std::to_string(items[k].index) + ":" + std::to_string(plan.shard_of[k]) + ",";
  plan.hash = fnv1a_hex(pairs);
  return plan;
}

std::vector<RunItem> shard_items(const std::vector<RunItem>& items, const ShardPlan& plan,
                                 const Shard& shard) {
  std::vector<RunItem> out;
  for (size_t k = 0; k < items.size(); ++k)
    if (plan.shard_of[k] == shard.index) out.push_back(items[k]);
  return out;
}

}  // namespace dv
