// Suite files (docs/suite-format.md): a named list of experiments, each a kind (the driver that
// runs it), one or more scenes, one or more strategies of the kind's family, fixed strategy
// parameters and a sweep (the cartesian product of parameter lists). Loading is strict: unknown
// keys, unknown kinds and bad values are InputErrors naming the file and the JSON path.
// expand_suite turns a suite into the deterministic, ordered list of runs that shards slice
// (shard_plan.h).
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/harness/run_item.h"

namespace dv {

// A strategy of the experiment's family by registered name, with parameters of its own (merged
// over the experiment's fixed parameters), run on the experiment's scenes whose path (as
// written) contains one of `scenes`, or on every scene when `scenes` is empty.
struct StrategySpec {
  std::string name;
  std::map<std::string, std::string> params;
  std::vector<std::string> scenes;

  bool runs_on(const std::string& scene) const {
    if (scenes.empty()) return true;
    for (const std::string& part : scenes)
      if (scene.find(part) != std::string::npos) return true;
    return false;
  }
};

struct ExperimentSpec {
  std::string name;
  std::string kind;  // driver name (driver.h)
  std::string description;
  std::vector<std::string> scenes;       // as written in the file
  std::vector<std::string> scene_paths;  // resolved (suite folder, working folder, data roots)
  std::vector<StrategySpec> strategies;
  std::map<std::string, std::string> params;  // fixed strategy parameters
  // Swept strategy parameters, in file order; the last one varies fastest.
  std::vector<std::pair<std::string, std::vector<std::string>>> sweep;
  std::map<std::string, std::string> settings;  // the driver's own knobs (image size, ...)
  std::vector<std::string> columns;             // report table columns; empty: driver default
  nlohmann::json paper;  // optional inline reference values printed beside the measured ones
  // Paper table files (docs/paper-tables.md) printed under the measured table, resolved like
  // scenes; the report names the paper's machine and ours.
  std::vector<std::string> paper_files;
  // Per paper file: null, or how its cells map to our rows ({"table", "where", "rows",
  // "columns"}, docs/suite-format.md), so the report prints ours beside each paper value.
  std::vector<nlohmann::json> paper_maps;
  nlohmann::json findings;  // optional claims decided by a declared comparison (findings.h)
  nlohmann::json pareto;    // optional {"error": [...], "cost": [...]}: fronts per scene
  nlohmann::json smoke;     // the experiment as `--smoke` runs it (overrides merged), or null
  nlohmann::json plots;     // optional plot specs for the plot script (array)
  // Every item run a second time as an A/A control (RunItem::aa_copy), after the experiment's
  // items in the same order.
  bool aa_duplicates = false;
};

struct Suite {
  std::string name;
  std::string description;
  std::string file;  // path it was loaded from
  std::string hash;  // FNV-1a 64 of the file's bytes, 16 hex digits
  int repeat = 3;
  std::vector<ExperimentSpec> experiments;
  // Per column ("metric:stat") or metric: the practical band of differences (findings.h), in the
  // metric's unit; a difference whose interval lies within it is a tie.
  std::map<std::string, double> practical_bands;
};

Suite load_suite(const std::string& path);
// The suite as `deepvox suite --smoke` runs it: every experiment with a `smoke` object replaced
// by its merged form (scene, strategy, sweep replaced; params and settings merged over).
Suite smoke_suite(const Suite& suite);
// `text` is the file's content; `path` names it in errors and anchors relative scene paths.
Suite parse_suite(const std::string& text, const std::string& path);
// A suite as a result folder recorded it (`deepvox report`): as parse_suite, but a claim recorded
// before claims named their timers gets the one time metric its columns compare, or "none" where
// they compare no time (a claim over several metrics keeps none and is refused as parse_suite
// refuses it); the hash is the recorded text's.
Suite parse_recorded_suite(const std::string& text, const std::string& path);

// Scenes x strategies x the sweep's cartesian product, per experiment in file order; an
// experiment with `aa_duplicates` then has a copy of each of its items.
std::vector<RunItem> expand_suite(const Suite& suite);

struct Shard {
  int index = 1;  // 1-based
  int count = 1;
  bool whole() const { return count == 1; }
};
// "I/N" with 1 <= I <= N; InputError(where) otherwise.
Shard parse_shard(const std::string& text, const std::string& where = "--shard");
// The items whose experiment name, kind or strategy contains `pattern` (all when empty).
std::vector<RunItem> filter_items(const std::vector<RunItem>& items, const std::string& pattern);

// Built-in suites: files experiments/suites/NAME.json under the data roots.
std::vector<std::string> builtin_suite_names();
// A file path as is when it exists, else the built-in suite of that name; InputError otherwise.
std::string resolve_suite_path(const std::string& name_or_file);
// Where repository files are found: $DEEPVOX_SOURCE_DIR, the source tree the binary was built
// from, and <executable>/../share/deepvox (installed bundles).
std::vector<std::string> data_roots();
// A repository-relative file (scene, paper table) beside `anchor_file`, in the working folder
// or under the data roots; the path as given when none exists (its reader names it).
std::string resolve_data_file(const std::string& path, const std::string& anchor_file);

std::string fnv1a_hex(const std::string& bytes);

}  // namespace dv
