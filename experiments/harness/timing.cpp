// Median, min and max of repeated pass timings, and the repetitions themselves (timing.h).
#include "experiments/harness/timing.h"

#include <algorithm>

#include "experiments/harness/driver.h"

namespace dv {

Spread spread_of(std::vector<double> samples) {
  std::sort(samples.begin(), samples.end());
  const size_t n = samples.size();
  const double median = n % 2 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
  return {median, samples.front(), samples.back()};
}

void PassTimes::add(const std::string& pass, double milliseconds) {
  for (auto& [name, samples] : passes_)
    if (name == pass) return samples.push_back(milliseconds);
  passes_.push_back({pass, {milliseconds}});
}

void PassTimes::emit(RowSink& rows, const std::string& prefix) const {
  for (const auto& [name, samples] : passes_) {
    const Spread s = spread_of(samples);
    const std::string metric = prefix + name + "_ms";
    rows.add(metric, "median", s.median, "ms");
    rows.add(metric, "min", s.min, "ms");
    rows.add(metric, "max", s.max, "ms");
    rows.add(metric, "repetitions", double(samples.size()), "count");
    rows.samples()["timings"][metric] = samples;
  }
}

}  // namespace dv
