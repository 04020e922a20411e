// The suite runner (runner.h).
#include "experiments/harness/runner.h"

#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

#include "core/error.h"
#include "cuda/device_memory.h"
#include "cuda/execute.h"
#include "experiments/harness/driver.h"
#include "experiments/harness/interrupt.h"
#include "experiments/harness/progress.h"
#include "experiments/harness/report.h"
#include "experiments/harness/run_folder.h"
#include "experiments/harness/run_metadata.h"
#include "experiments/harness/scene_cache.h"
#include "experiments/harness/shard_plan.h"

namespace dv {

namespace fs = std::filesystem;

namespace {

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError(path.string(), "cannot write");
  out << text;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string describe(const RunItem& item) {
  return item.experiment_name + ": " + item.strategy +
         (item.params.empty() ? "" : " " + item.params_text()) + " on " + item.scene;
}

}  // namespace

SuiteOutcome run_suite(const SuiteOptions& o) {
  const std::string path = resolve_suite_path(o.suite);
  const Suite loaded = load_suite(path);
  const Suite suite = o.smoke ? smoke_suite(loaded) : loaded;
  const Backend backend = o.backend.empty() ? default_backend() : parse_backend(o.backend);
  require_backend(backend);
  const Shard shard = o.shard.empty() ? Shard{} : parse_shard(o.shard);
  const std::vector<RunItem> all = expand_suite(suite);
  const std::vector<RunItem> chosen = filter_items(all, o.only);
  const ItemCosts costs = item_costs(chosen, suite, o.costs, o.out);
  const ShardPlan plan = plan_shards(chosen, costs, shard.count);
  const std::vector<RunItem> items = shard_items(chosen, plan, shard);
  if (o.repeat < 0) throw InputError("--repeat", "expected a positive count");
  const int repeat = o.repeat > 0 ? o.repeat : suite.repeat;

  const std::string sha = build_git_sha();
  const fs::path dir = make_run_folder(
      o.out, suite.name, sha,
      shard.whole() ? ""
                    : "shard" + std::to_string(shard.index) + "of" + std::to_string(shard.count));
  write_text(dir / "command.txt", command_line() + "\n");
  write_text(dir / "suite.json", read_text(path));

  nlohmann::json meta = {{"suite", suite.name},
                         {"suite_file", path},
                         {"suite_hash", suite.hash},
                         {"repeat", repeat},
                         {"only", o.only},
                         {"smoke", o.smoke},
                         {"shard",
                          {{"index", shard.index},
                           {"count", shard.count},
                           {"cost_source", costs.source},
                           {"assignment_hash", plan.hash},
                           {"cost", plan.load[size_t(shard.index - 1)]}}},
                         {"items_in_suite", all.size()},
                         {"items", items.size()},
                         {"run", run_metadata(backend)}};
  SceneCache scenes(backend);
  RunContext context{backend, repeat, dir, &scenes};
  std::map<std::string, std::unique_ptr<Driver>> drivers;
  std::vector<Row> rows;
  nlohmann::json params = nlohmann::json::array();
  SuiteOutcome outcome;
  outcome.folder = dir.string();
  outcome.total = int(items.size());
  Progress progress(outcome.total, o.progress && Progress::stderr_is_terminal(), o.status_file);
  const InterruptScope ctrl_c;  // until the report is written: a Ctrl-C then still leaves it
  for (const RunItem& item : items) {
    if (interrupt_requested()) break;
    progress.start(outcome.done, describe(item));
    RowSink sink(suite.name, item, rows);
    nlohmann::json echoed = {{"item", item.index},       {"experiment", item.experiment_name},
                             {"scene", item.scene},      {"strategy", item.strategy},
                             {"requested", item.params}, {"settings", item.settings}};
    try {
      auto& driver = drivers[item.kind];
      if (!driver) driver = driver_registry().create(item.kind);
      echoed["echoed"] = driver->run(item, context, sink);
    } catch (const SkippedRun& e) {
      sink.add("skipped", "value", 1.0, "", e.what());
      echoed["skipped"] = e.what();
      ++outcome.skipped;
    } catch (const std::exception& e) {
      sink.add("failed", "value", 1.0, "", e.what());
      echoed["error"] = e.what();
      ++outcome.failed;
      progress.finish();
      std::fprintf(stderr, "deepvox suite: %s failed: %s\n", describe(item).c_str(), e.what());
    }
    params.push_back(std::move(echoed));
    ++outcome.done;
    write_rows_csv((dir / "rows.csv").string(), rows);  // a crash later loses nothing finished
  }
  progress.finish();
  progress.write_status(outcome.done, "finished");
  outcome.interrupted = interrupt_requested() && outcome.done < outcome.total;
  meta["done"] = outcome.done;
  meta["failed"] = outcome.failed;
  meta["skipped"] = outcome.skipped;
  meta["interrupted"] = outcome.interrupted;
  meta["elapsed_s"] = progress.elapsed_seconds();
  write_rows_csv((dir / "rows.csv").string(), rows);
  write_text(dir / "params.json", params.dump(1) + "\n");
  write_text(dir / "meta.json", meta.dump(1) + "\n");
  if (o.report) build_report(dir.string());
  outcome.exit_code = outcome.interrupted ? 130 : outcome.failed ? 3 : 0;
  return outcome;
}

std::string list_suites() {
  std::string out;
  for (const std::string& name : builtin_suite_names()) {
    const Suite s = load_suite(resolve_suite_path(name));
    out += name + std::string(name.size() < 12 ? 12 - name.size() : 1, ' ') + s.description + "\n";
  }
  return out;
}

}  // namespace dv
