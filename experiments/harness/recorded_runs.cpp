// The independent runs a result folder pools (recorded_runs.h).
#include "experiments/harness/recorded_runs.h"

#include "core/error.h"
#include "core/json_reader.h"
#include "experiments/harness/durable_file.h"
#include "experiments/harness/run_journal.h"

namespace dv {

namespace fs = std::filesystem;

namespace {

// InputError naming `other` when it is no run of the suite file `dir` ran.
void check_same_suite(const fs::path& other, const fs::path& dir, const std::string& suite,
                      const std::string& suite_hash) {
  const Json meta = read_run_state(other).meta;
  if (meta.value("suite", "") != suite || meta.value("suite_hash", "") != suite_hash)
    throw InputError(other.string(), "not a run of the same suite file as " + dir.string() +
                                         " (suite " + meta.value("suite", "") + ", hash " +
                                         meta.value("suite_hash", "") + ")");
}

}  // namespace

std::vector<fs::path> recorded_runs(const fs::path& dir, const std::string& suite,
                                    const std::string& suite_hash) {
  const fs::path file = dir / "runs.json";
  if (!fs::is_regular_file(file)) return {};
  const Json runs = parse_json_file(file.string());
  if (!runs.contains("runs") || !runs["runs"].is_array())
    throw InputError(file.string(), "expected {\"runs\": [folder, ...]}");
  std::vector<fs::path> out;
  for (const Json& r : runs["runs"]) {
    if (!r.is_string()) throw InputError(file.string(), "runs: expected folder names");
    out.push_back(dir / r.get<std::string>());
    check_same_suite(out.back(), dir, suite, suite_hash);
  }
  return out;
}

void record_runs(const std::string& folder, const std::vector<std::string>& others) {
  fs::path dir = fs::absolute(folder).lexically_normal();
  if (!dir.has_filename()) dir = dir.parent_path();  // "DIR/" names DIR
  Json runs = Json::array();
  for (const std::string& o : others) {
    if (!fs::is_directory(o)) throw InputError(o, "no such result folder");
    runs.push_back(fs::relative(fs::absolute(o), dir).string());
  }
  const Json meta = read_run_state(dir).meta;
  for (const Json& r : runs)
    check_same_suite(dir / r.get<std::string>(), dir, meta.value("suite", ""),
                     meta.value("suite_hash", ""));
  write_file_atomically(dir / "runs.json", Json{{"runs", runs}}.dump(1) + "\n");
}

}  // namespace dv
