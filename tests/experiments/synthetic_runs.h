// Synthetic runs for the findings' tests: items with params and, per run, rows and timing
// samples (as a result folder's rows.csv and samples/ give them), built with known effects.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "experiments/harness/findings.h"
#include "experiments/harness/rows.h"

namespace dv::test {

// Synthetic runs: items with params and, per run, rows and timing samples.
class Runs {
 public:
  explicit Runs(int count) : views_(size_t(count)), rows_(size_t(count)) {}
  // A timed item: `samples[run]` its repetitions in each run; the rows carry their median.
  void timed(int item, const std::string& params, const std::string& metric,
             const std::vector<std::vector<double>>& samples) {
    for (size_t run = 0; run < samples.size(); ++run) {
      std::vector<double> s = samples[run];
      std::sort(s.begin(), s.end());
      add(run, item, params, metric, "median", s[s.size() / 2], "ms");
      views_[run].samples[item]["timings"][metric] = samples[run];
    }
  }
  // A value row in every run.
  void value(int item, const std::string& params, const std::string& metric, double v,
             const std::string& unit = "count") {
    for (size_t run = 0; run < views_.size(); ++run)
      add(run, item, params, metric, "value", v, unit);
  }
  // Signed probe errors of one class (first run's samples) and the rows' mean of |error|.
  void errors(int item, const std::string& params, const std::string& name,
              const std::vector<double>& errors) {
    double sum = 0.0;
    for (double e : errors) sum += std::abs(e);
    for (size_t run = 0; run < views_.size(); ++run)
      for (const std::string& c : {name, std::string("all")})
        add(run, item, params, "probe_error_" + c, "mean", sum / double(errors.size()), "T");
    views_[0].samples[item]["probe_errors"][name] = errors;
  }
  std::vector<RunView> views() {
    for (size_t run = 0; run < views_.size(); ++run) {
      views_[run].items.clear();
      for (const Row& r : rows_[run]) views_[run].items[r.item].push_back(&r);
    }
    return views_;
  }
  void drop_samples() {
    for (RunView& v : views_) v.samples.clear();
  }

 private:
  void add(size_t run, int item, const std::string& params, const std::string& metric,
           const std::string& stat, double value, const std::string& unit) {
    Row r;
    r.item = item;
    r.strategy = "dsm";
    r.scene = "scenes/a.json";
    r.params = params;
    r.metric = metric;
    r.stat = stat;
    r.value = value;
    r.unit = unit;
    rows_[run].push_back(r);
  }
  std::vector<RunView> views_;
  std::vector<std::vector<Row>> rows_;  // stable: views are rebuilt from them
};

// Five repetitions around `centre` (+-2 %).
inline std::vector<double> reps(double centre) {
  return {centre * 0.98, centre * 0.99, centre, centre * 1.01, centre * 1.02};
}

}  // namespace dv::test
