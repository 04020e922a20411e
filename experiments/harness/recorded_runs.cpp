// The independent runs a result folder pools (recorded_runs.h).
#include "experiments/harness/recorded_runs.h"

#include <algorithm>
#include <map>
#include <tuple>

#include "core/error.h"
#include "core/json_reader.h"
#include "experiments/harness/durable_file.h"
#include "experiments/harness/lossy.h"
#include "experiments/harness/run_journal.h"
#include "experiments/harness/timing.h"

namespace dv {

namespace fs = std::filesystem;

namespace {

// InputError naming `other` when it is no run of the suite file `dir` ran.
void check_same_suite(const fs::path& other, const fs::path& dir, const std::string& suite,
                      const std::string& suite_hash) {
  const Json meta = read_run_meta(other);
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
  const Json meta = read_run_meta(dir);
  for (const Json& r : runs)
    check_same_suite(dir / r.get<std::string>(), dir, meta.value("suite", ""),
                     meta.value("suite_hash", ""));
  write_file_atomically(dir / "runs.json", Json{{"runs", runs}}.dump(1) + "\n");
}

// The rows the tables and plots show: the first run's, each value the median over the runs of
// that item's row with the same metric and statistic (a timing: the median of the runs'
// medians; values that do not vary between runs stay), and with several runs a timing's min and
// max the lowest and highest of the runs' medians (the run-to-run range) instead of one run's
// repetitions; a loss count (lossy.h) the largest over the runs. With one run its rows.
std::vector<Row> rows_over_runs(const std::vector<RunState>& states) {
  std::vector<Row> out = states[0].rows;
  if (states.size() < 2) return out;
  using Key = std::tuple<int, std::string, std::string>;
  std::map<Key, std::vector<double>> values;
  for (const RunState& run : states)
    for (const Row& r : run.rows) values[{r.item, r.metric, r.stat}].push_back(r.value);
  for (Row& r : out) {
    const bool range = r.stat == "min" || r.stat == "max";
    const auto medians = values.find({r.item, r.metric, "median"});
    if (range && medians != values.end()) {
      const auto [lo, hi] = std::minmax_element(medians->second.begin(), medians->second.end());
      r.value = r.stat == "min" ? *lo : *hi;
    } else if (is_loss_metric(r.metric)) {
      const std::vector<double>& v = values[{r.item, r.metric, r.stat}];
      r.value = *std::max_element(v.begin(), v.end());  // a loss in any run shows
    } else if (!range) {
      r.value = spread_of(values[{r.item, r.metric, r.stat}]).median;
    }
  }
  return out;
}

}  // namespace dv
