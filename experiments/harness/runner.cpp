// The suite runner (runner.h).
#include "experiments/harness/runner.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <new>

#include "core/error.h"
#include "cuda/execute.h"
#include "cuda/memory_check.h"
#include "experiments/harness/driver.h"
#include "experiments/harness/interrupt.h"
#include "experiments/harness/progress.h"
#include "experiments/harness/report.h"
#include "experiments/harness/run_journal.h"
#include "experiments/harness/run_metadata.h"
#include "experiments/harness/run_order.h"
#include "experiments/harness/scene_cache.h"
#include "experiments/harness/shard_plan.h"

namespace dv {

namespace fs = std::filesystem;

namespace {

// One entry of meta.json's "attempts": who ran (a part of) the folder, with what.
Json attempt_entry(const std::string& suite_hash) {
  return {{"utc_time", utc_time_now()}, {"host", host_name()},
          {"pid", int(getpid())},       {"git_sha", build_git_sha()},
          {"suite_hash", suite_hash},   {"command_line", command_line()}};
}

// What a call runs: the items still to run, into which folder.
struct Plan {
  Suite suite;
  Backend backend = Backend::cpu;
  int repeat = 1;
  std::vector<RunItem> items;
  Json meta;
  RunJournal journal;
  RunState before;  // the folder's complete part before this call (empty for a new run)
  int attempt = 1;
};

// What both kinds of run tell the journal about themselves.
JournalRequest journal_request(const SuiteOptions& o, const Suite& suite, const std::string& path,
                               const Shard& shard) {
  JournalRequest r;
  r.out = o.out;
  r.suite = suite.name;
  r.suite_file = path;
  r.suite_hash = suite.hash;
  r.git_sha = build_git_sha();
  r.shard_index = shard.index;
  r.shard_count = shard.count;
  return r;
}

Plan new_run(const SuiteOptions& o) {
  Plan p;
  const std::string path = resolve_suite_path(o.suite);
  const Suite loaded = load_suite(path);
  p.suite = o.smoke ? smoke_suite(loaded) : loaded;
  p.backend = o.backend.empty() ? default_backend() : parse_backend(o.backend);
  require_backend(p.backend);
  const Shard shard = o.shard.empty() ? Shard{} : parse_shard(o.shard);
  const std::vector<RunItem> all = expand_suite(p.suite);
  const std::vector<RunItem> chosen = filter_items(all, o.only);
  const ItemCosts costs = item_costs(chosen, p.suite, o.costs, o.out);
  const ShardPlan plan = plan_shards(chosen, costs, shard.count);
  p.items = shard_items(chosen, plan, shard);
  if (o.permute) p.items = protocol_order(p.items, p.suite, o.order_seed);
  if (o.repeat < 0) throw InputError("--repeat", "expected a positive count");
  p.repeat = o.repeat > 0 ? o.repeat : p.suite.repeat;
  Json planned = Json::array();
  for (const RunItem& item : p.items) planned.push_back(item.index);
  p.meta = {{"suite", p.suite.name},
            {"suite_file", path},
            {"suite_hash", p.suite.hash},
            {"repeat", p.repeat},
            {"only", o.only},
            {"smoke", o.smoke},
            {"shard",
             {{"index", shard.index},
              {"count", shard.count},
              {"cost_source", costs.source},
              {"assignment_hash", plan.hash},
              {"cost", plan.load[size_t(shard.index - 1)]}}},
            {"items_in_suite", all.size()},
            {"items", p.items.size()},
            {"planned_items", planned},
            {"order", o.permute ? Json{{"protocol", "replicate"},
                                       {"seed", o.order_seed},
                                       {"rule",
                                        "items permuted with the seed, the two sides of "
                                        "each comparison claim in adjacent pairs, ABBA"}}
                                : Json{{"protocol", "suite order"}}},
            {"state", "running"},
            {"attempts", Json::array({attempt_entry(p.suite.hash)})},
            {"run", run_metadata(p.backend)}};
  JournalRequest r = journal_request(o, p.suite, path, shard);
  r.tag = shard.whole()
              ? ""
              : "shard" + std::to_string(shard.index) + "of" + std::to_string(shard.count);
  r.meta = p.meta;
  r.suite_text = read_file_text(path);
  r.command = command_line();
  p.journal = std::move(RunJournal::open_or_resume(r).journal);
  return p;
}

Plan resumed_run(const SuiteOptions& o) {
  const std::string path =
      o.suite.empty() ? RunJournal::resumed_suite_file(o.resume_dir) : resolve_suite_path(o.suite);
  const Suite loaded = load_suite(path);
  const Shard shard = o.shard.empty() ? Shard{} : parse_shard(o.shard);
  JournalRequest r = journal_request(o, loaded, path, shard);
  r.resume = true;
  r.resume_dir = o.resume_dir;
  r.force = o.force;
  using Given = JournalRequest::GivenOption;
  if (!o.backend.empty())
    r.given.push_back(Given{"--backend", o.backend, [](const Json& meta) -> Json {
                              return meta["run"].value("backend", "");
                            }});
  if (o.repeat > 0)
    r.given.push_back(Given{"--repeat", o.repeat, [](const Json& meta) { return meta["repeat"]; }});
  if (!o.only.empty())
    r.given.push_back(Given{"--only", o.only, [](const Json& meta) { return meta["only"]; }});
  if (o.smoke)
    r.given.push_back(Given{"--smoke", o.smoke,
                            [](const Json& meta) -> Json { return meta.value("smoke", false); }});
  if (!o.shard.empty())
    r.given.push_back(Given{"--shard", o.shard, [](const Json& meta) -> Json {
                              return std::to_string(meta["shard"].value("index", 1)) + "/" +
                                     std::to_string(meta["shard"].value("count", 1));
                            }});
  OpenedRun opened = RunJournal::open_or_resume(r);
  Plan p;
  p.journal = std::move(opened.journal);
  p.before = std::move(opened.before);
  const Json& meta = p.before.meta;
  p.suite = meta.value("smoke", false) ? smoke_suite(loaded) : loaded;
  p.backend = parse_backend(meta["run"].value("backend", ""));
  require_backend(p.backend);
  p.repeat = meta["repeat"].get<int>();
  std::map<int, RunItem> by_index;
  for (RunItem& item : expand_suite(p.suite)) by_index[item.index] = std::move(item);
  for (int index : p.before.missing) {
    if (!by_index.count(index))
      throw InputError(p.journal.dir().string(), "item " + std::to_string(index) +
                                                     " of the folder's plan is not in " + path +
                                                     "; it cannot be resumed with this suite file");
    p.items.push_back(by_index[index]);
  }
  p.meta = p.before.meta;
  if (p.before.finished) return p;  // nothing to run, nothing to change
  Json attempt = attempt_entry(loaded.hash);
  if (!opened.forced.empty()) {
    attempt["forced"] = opened.forced;
    p.meta["mixed"] = true;
  }
  p.meta["attempts"].push_back(attempt);
  p.attempt = int(p.meta["attempts"].size());
  p.meta["state"] = "running";
  p.journal.write_meta(p.meta);
  p.journal.add_command(command_line());
  return p;
}

using Drivers = std::map<std::string, std::unique_ptr<Driver>>;

// Runs one item into `sink`: "ok", "skipped" or "failed" (a row says why; out of memory also
// the bytes asked for). A ResultWriteError passes: the folder takes no more results.
std::string run_item(const RunItem& item, RunContext& context, Drivers& drivers, RowSink& sink,
                     Json& echoed) {
  const auto fail = [&](const std::string& why) {
    sink.add("failed", "value", 1.0, "", why);
    echoed["error"] = why;
    return std::string("failed");
  };
  try {
    auto& driver = drivers[item.kind];
    if (!driver) driver = driver_registry().create(item.kind);
    echoed["echoed"] = driver->run(item, context, sink);
    return "ok";
  } catch (const ResultWriteError&) {
    throw;
  } catch (const SkippedRun& e) {
    sink.add("skipped", "value", 1.0, "", e.what());
    echoed["skipped"] = e.what();
    return "skipped";
  } catch (const OutOfMemory& e) {
    sink.add("out_of_memory", "bytes_asked", double(e.bytes()), "bytes");
    echoed["out_of_memory_bytes"] = e.bytes();
    return fail(std::string("out of memory: ") + e.what());
  } catch (const std::bad_alloc&) {
    return fail("out of host memory (std::bad_alloc)");
  } catch (const std::exception& e) {
    return fail(e.what());
  }
}

// The error a run stops with when its folder takes no more results.
ResultWriteError stopped(const ResultWriteError& e, Plan& p, const SuiteOptions& o, int done,
                         int total) {
  Json meta = p.meta;
  meta["state"] = "stopped";
  meta["stopped_by"] = e.what();
  try {
    p.journal.write_meta(meta);
  } catch (const ResultWriteError&) {
    // The disk is still full: meta.json stays as it was, which reads as a killed run.
  }
  const std::string dir = p.journal.dir().string();
  return ResultWriteError(std::string(e.what()) + "\nthe run stopped; " + std::to_string(done) +
                          " of " + std::to_string(total) +
                          " experiments are complete and kept in " + dir +
                          "\nfree space or make the folder writable, then resume: deepvox suite " +
                          (o.suite.empty() ? "" : o.suite + " ") + "--resume " + dir);
}

}  // namespace

SuiteOutcome run_suite(const SuiteOptions& o) {
  // Before the folder exists: a Ctrl-C from then on stops after the current item and still
  // leaves a report.
  const InterruptScope ctrl_c;
  Plan p = o.resume ? resumed_run(o) : new_run(o);
  const fs::path dir = p.journal.dir();
  SuiteOutcome outcome;
  outcome.folder = dir.string();
  outcome.total = int(p.meta["planned_items"].size());
  outcome.done = p.before.done;
  outcome.failed = p.before.failed;
  outcome.skipped = p.before.skipped;
  if (p.before.finished) {
    p.journal.close();
    if (o.report) build_report(dir.string());
    outcome.exit_code = outcome.failed ? kSuiteRowsFailed : kSuiteDone;
    return outcome;
  }
  SceneCache scenes(p.backend);
  RunContext context{p.backend, p.repeat, dir, &scenes};
  Drivers drivers;
  Json params = p.before.params;
  Progress progress(outcome.total, o.progress && Progress::stderr_is_terminal(), o.status_file);
  try {
    for (const RunItem& item : p.items) {
      if (interrupt_requested()) break;
      progress.start(outcome.done, item.describe());
      const auto item_start = std::chrono::steady_clock::now();
      std::vector<Row> rows;
      RowSink sink(p.suite.name, item, rows);
      Json echoed = {{"item", item.index},       {"experiment", item.experiment_name},
                     {"scene", item.scene},      {"strategy", item.strategy},
                     {"requested", item.params}, {"settings", item.settings}};
      if (item.aa_copy) echoed["aa_copy"] = true;
      const std::string result = run_item(item, context, drivers, sink, echoed);
      if (result == "failed") {
        progress.finish();
        std::fprintf(stderr, "deepvox suite: %s failed: %s\n", item.describe().c_str(),
                     echoed["error"].get<std::string>().c_str());
      }
      if (!sink.samples().is_null()) {
        std::error_code ec;
        fs::create_directories(dir / "samples", ec);
        if (ec) throw ResultWriteError((dir / "samples").string(), ec.message());
        write_file_atomically(dir / "samples" / (std::to_string(item.index) + ".json"),
                              sink.samples().dump() + "\n");
      }
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - item_start).count();
      // Synced: survives a kill.
      p.journal.record(item.index, p.attempt, rows, result, echoed, seconds);
      params.push_back(std::move(echoed));
      ++outcome.done;
      ++outcome.ran_now;
      outcome.failed += result == "failed";
      outcome.skipped += result == "skipped";
    }
    progress.finish();
    progress.write_status(outcome.done, "finished");
    const bool complete = outcome.done >= outcome.total;
    outcome.interrupted = interrupt_requested() && !complete;
    std::stable_sort(params.begin(), params.end(), [](const Json& a, const Json& b) {
      return a["item"].get<int>() < b["item"].get<int>();
    });
    p.meta["done"] = outcome.done;
    p.meta["failed"] = outcome.failed;
    p.meta["skipped"] = outcome.skipped;
    p.meta["interrupted"] = outcome.interrupted;
    p.meta["elapsed_s"] = p.meta.value("elapsed_s", 0.0) + progress.elapsed_seconds();
    p.meta["state"] = complete ? "finished" : "interrupted";
    p.meta.erase("stopped_by");
    write_file_atomically(dir / "params.json", params.dump(1) + "\n");
    p.journal.write_meta(p.meta);
  } catch (const ResultWriteError& e) {
    progress.finish();
    throw stopped(e, p, o, outcome.done, outcome.total);
  }
  p.journal.close();  // releases the folder's lock: the report reads it as not being written
  if (o.report) build_report(dir.string());
  outcome.exit_code = outcome.interrupted ? kSuiteInterrupted
                      : outcome.failed    ? kSuiteRowsFailed
                                          : kSuiteDone;
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
