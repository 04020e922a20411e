// Merging shard folders (merge.h).
#include "experiments/harness/merge.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/json_reader.h"
#include "experiments/harness/report.h"
#include "experiments/harness/rows.h"
#include "experiments/harness/run_folder.h"
#include "experiments/harness/run_metadata.h"

namespace dv {

namespace fs = std::filesystem;

namespace {

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "cannot read");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

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
  std::map<int, std::string> by_index;
  Json first;
  Json unfinished = Json::array();
  for (const std::string& folder : folders) {
    const fs::path meta_path = fs::path(folder) / "meta.json";
    if (!fs::is_regular_file(meta_path) && allow_missing) {
      unfinished.push_back(folder);
      continue;
    }
    if (!fs::is_regular_file(meta_path))
      throw InputError(folder, "not a suite result folder (no meta.json)");
    const Json meta = parse_json_file(meta_path.string());
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
    if (by_index.count(index))
      throw InputError(
          folder, "shard " + std::to_string(index) + " given twice (also " + by_index[index] + ")");
    by_index[index] = folder;
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
  const fs::path dir =
      make_run_folder(root, suite, first["run"]["git_sha"].get<std::string>(), "merged");
  std::vector<Row> rows;
  Json params = Json::array(), shards = Json::array();
  std::string commands = command_line() + "\n";
  int done = 0, failed = 0, skipped = 0, items = 0;
  bool interrupted = false;
  for (const auto& [index, folder] : by_index) {
    const fs::path f(folder);
    const Json meta = parse_json_file((f / "meta.json").string());
    const std::vector<Row> shard_rows = read_rows_csv((f / "rows.csv").string());
    rows.insert(rows.end(), shard_rows.begin(), shard_rows.end());
    for (const Json& p : parse_json_file((f / "params.json").string())) params.push_back(p);
    commands += "# shard " + std::to_string(index) + ": " + read_text(f / "command.txt");
    done += meta["done"].get<int>();
    failed += meta["failed"].get<int>();
    skipped += meta.value("skipped", 0);
    items += meta["items"].get<int>();
    interrupted |= meta["interrupted"].get<bool>();
    shards.push_back({{"index", index}, {"folder", folder}, {"run", meta["run"]}});
    if (fs::is_directory(f / "images"))
      fs::copy(f / "images", dir / "images",
               fs::copy_options::recursive | fs::copy_options::skip_existing);
  }
  sort_rows_by_item(rows);
  std::stable_sort(params.begin(), params.end(), [](const Json& a, const Json& b) {
    return a["item"].get<int>() < b["item"].get<int>();
  });
  Json meta = first;
  meta["shard"] = {{"index", 1}, {"count", 1}};
  meta["merged_from"] = shards;
  meta["scale_out"] = scale_out(shards);
  if (!missing.empty()) {
    meta["missing_shards"] = missing_list;
    meta["unfinished_folders"] = unfinished;
  }
  meta["done"] = done;
  meta["failed"] = failed;
  meta["skipped"] = skipped;
  meta["items"] = items;
  meta["interrupted"] = interrupted;
  write_rows_csv((dir / "rows.csv").string(), rows);
  std::ofstream(dir / "params.json") << params.dump(1) << "\n";
  std::ofstream(dir / "meta.json") << meta.dump(1) << "\n";
  std::ofstream(dir / "command.txt") << commands;
  fs::copy_file(fs::path(by_index.begin()->second) / "suite.json", dir / "suite.json");
  build_report(dir.string());
  return dir.string();
}

}  // namespace dv
