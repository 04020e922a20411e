// Merging shard folders (merge.h).
#include "experiments/harness/merge.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "core/error.h"
#include "core/json_reader.h"
#include "experiments/harness/durable_file.h"
#include "experiments/harness/report.h"
#include "experiments/harness/rows.h"
#include "experiments/harness/run_journal.h"
#include "experiments/harness/run_metadata.h"

namespace dv {

namespace fs = std::filesystem;

namespace {

void require_same(const Json& a, const Json& b, const std::string& what, const std::string& dir) {
  if (a != b)
    throw InputError(dir,
                     "shard of a different " + what + " (" + a.dump() + " vs " + b.dump() + ")");
}

// "2 GPUs on 1 host", "2 CPU workers on 1 host": a GPU is a (host, device, visible devices)
// triple of a CUDA shard.
Json scale_out(const Json& shards) {
  std::set<std::string> hosts, gpus;
  bool cuda = false;
  for (const Json& s : shards) {
    const Json& run = s["run"];
    const std::string host = run.value("host", "unknown");
    hosts.insert(host);
    if (run.value("backend", "") == "cuda") {
      cuda = true;
      gpus.insert(host + "|" + run.value("device", "") + "|" +
                  run.value("cuda_visible_devices", std::to_string(s["index"].get<int>())));
    }
  }
  const size_t workers = cuda ? gpus.size() : shards.size();
  const std::string summary = std::to_string(workers) + (cuda ? " GPU" : " CPU worker") +
                              (workers == 1 ? "" : "s") + " on " + std::to_string(hosts.size()) +
                              " host" + (hosts.size() == 1 ? "" : "s");
  return {{"summary", summary},
          {"gpus", cuda ? workers : 0},
          {"hosts", std::vector<std::string>(hosts.begin(), hosts.end())}};
}

}  // namespace

std::string merge_shards(const std::vector<std::string>& folders, const std::string& out,
                         bool allow_missing) {
  if (folders.empty()) throw InputError("merge", "no shard folders given");
  std::map<int, RunState> by_index;
  Json first;
  Json unfinished = Json::array();
  for (const std::string& folder : folders) {
    if (!fs::is_regular_file(fs::path(folder) / "meta.json") && allow_missing) {
      unfinished.push_back(folder);
      continue;
    }
    RunState state = read_run_state(folder);
    const Json& meta = state.meta;
    if (first.is_null()) first = meta;
    require_same(meta["suite"], first["suite"], "suite", folder);
    require_same(meta["suite_hash"], first["suite_hash"], "suite file (hash)", folder);
    require_same(meta["run"]["git_sha"], first["run"]["git_sha"], "commit", folder);
    require_same(meta["shard"]["count"], first["shard"]["count"], "shard count", folder);
    require_same(meta["shard"].value("cost_source", Json()),
                 first["shard"].value("cost_source", Json()), "cost source (--costs)", folder);
    require_same(meta["shard"].value("assignment_hash", Json()),
                 first["shard"].value("assignment_hash", Json()), "shard assignment", folder);
    require_same(meta["only"], first["only"], "--only", folder);
    require_same(meta.value("smoke", false), first.value("smoke", false), "--smoke", folder);
    require_same(meta["repeat"], first["repeat"], "--repeat", folder);
    const int index = meta["shard"]["index"].get<int>();
    const std::string shard = "shard " + std::to_string(index);
    if (by_index.count(index))
      throw InputError(folder, shard + " given twice (also " + by_index[index].dir.string() + ")");
    if (state.locked)
      throw InputError(
          folder, shard + " is still being written by a deepvox process; merge " + "when it ended");
    if (!state.unchecked_writer.empty() && !allow_missing)
      throw InputError(folder, shard + " may still be written by a deepvox process on another " +
                                   "host (" + state.unchecked_writer +
                                   "); merge when it ended, or with --allow-missing");
    if (!state.missing.empty() && !allow_missing)
      throw InputError(folder, shard + " is unfinished: " + std::to_string(state.done) + " of " +
                                   std::to_string(state.done + int(state.missing.size())) +
                                   " experiments complete; resume it (deepvox suite " +
                                   meta.value("suite_file", "SUITE") + " --shard " +
                                   std::to_string(index) + "/" +
                                   std::to_string(meta["shard"]["count"].get<int>()) +
                                   " --resume " + folder + ") or merge with --allow-missing");
    by_index[index] = std::move(state);
  }
  if (first.is_null()) throw InputError("merge", "no finished shard among the folders given");
  const int count = first["shard"]["count"].get<int>();
  std::string missing;
  Json missing_list = Json::array();
  for (int i = 1; i <= count; ++i)
    if (!by_index.count(i)) {
      missing += (missing.empty() ? "" : ", ") + std::to_string(i);
      missing_list.push_back(i);
    }
  if (!missing.empty() && !allow_missing)
    throw InputError("merge", "missing shard(s) " + missing + " of " + std::to_string(count));

  const std::string suite = first["suite"].get<std::string>();
  const fs::path root =
      out.empty() ? fs::path(folders.front()).parent_path().parent_path() : fs::path(out);
  std::vector<Row> rows;
  Json params = Json::array(), shards = Json::array(), planned = Json::array(),
       missing_items = Json::array(), partial = Json::array();
  std::string commands = command_line() + "\n";
  int done = 0, failed = 0, skipped = 0, items = 0;
  bool interrupted = false, mixed = false;
  for (const auto& [index, state] : by_index) {
    const fs::path& f = state.dir;
    const Json& meta = state.meta;
    rows.insert(rows.end(), state.rows.begin(), state.rows.end());
    for (const Json& p : state.params) params.push_back(p);
    for (const Json& i : meta.value("planned_items", Json::array())) planned.push_back(i);
    for (int i : state.missing) missing_items.push_back(i);
    if (!state.missing.empty()) partial.push_back(index);
    commands += "# shard " + std::to_string(index) + ": " + read_file_text(f / "command.txt");
    done += state.done;
    failed += state.failed;
    skipped += state.skipped;
    items += meta["items"].get<int>();
    interrupted |= meta.value("interrupted", false);
    mixed |= meta.value("mixed", false);
    shards.push_back({{"index", index},
                      {"folder", f.string()},
                      {"attempts", meta.value("attempts", Json::array()).size()},
                      {"run", meta["run"]}});
  }
  sort_rows_by_item(rows);
  std::stable_sort(params.begin(), params.end(), [](const Json& a, const Json& b) {
    return a["item"].get<int>() < b["item"].get<int>();
  });
  std::sort(planned.begin(), planned.end());
  std::sort(missing_items.begin(), missing_items.end());
  Json meta = first;
  meta["shard"] = {{"index", 1}, {"count", 1}};
  meta["merged_from"] = shards;
  meta["scale_out"] = scale_out(shards);
  if (!missing.empty()) {
    meta["missing_shards"] = missing_list;
    meta["unfinished_folders"] = unfinished;
  }
  if (!partial.empty()) meta["partial_shards"] = partial;
  meta["planned_items"] = planned;
  meta["missing_items"] = missing_items;
  meta["done"] = done;
  meta["failed"] = failed;
  meta["skipped"] = skipped;
  meta["items"] = items;
  meta["interrupted"] = interrupted;
  meta["mixed"] = mixed;
  meta["state"] = "finished";
  meta.erase("attempts");
  meta.erase("stopped_by");
  const fs::path dir = make_filled_run_folder(
      root, suite, first["run"]["git_sha"].get<std::string>(), "merged", [&](const fs::path& tmp) {
        write_rows_csv((tmp / "rows.csv").string(), rows);
        write_file_atomically(tmp / "params.json", params.dump(1) + "\n");
        write_file_atomically(tmp / "meta.json", meta.dump(1) + "\n");
        write_file_atomically(tmp / "command.txt", commands);
        write_file_atomically(tmp / "suite.json",
                              read_file_text(by_index.begin()->second.dir / "suite.json"));
        for (const auto& [index, state] : by_index)
          for (const char* sub : {"images", "samples"})
            if (fs::is_directory(state.dir / sub))
              fs::copy(state.dir / sub, tmp / sub,
                       fs::copy_options::recursive | fs::copy_options::skip_existing);
      });
  build_report(dir.string());
  return dir.string();
}

}  // namespace dv
