// A/A controls measured from an experiment's duplicate items (aa_controls.h).
#include "experiments/harness/aa_controls.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <tuple>

#include "core/number_text.h"

namespace dv {

namespace {

constexpr const char* kCopyTerm = "aa=copy";

// The params of a row less the A/A copy's term, and whether it had it.
std::pair<std::string, bool> params_without_copy(const std::string& params) {
  std::istringstream in(params);
  std::string out;
  bool copy = false;
  for (std::string word; in >> word;) {
    if (word == kCopyTerm) {
      copy = true;
      continue;
    }
    out += (out.empty() ? "" : " ") + word;
  }
  return {out, copy};
}

// One item's timings of `metric`, per run ([run][repetition]; empty where not measured).
RunSamples timings_of(int index, const std::string& metric, const std::vector<RunView>& runs) {
  RunSamples out;
  for (const RunView& run : runs) {
    std::vector<double> samples;
    const auto it = run.samples.find(index);
    if (it != run.samples.end() && it->second.is_object() && it->second.contains("timings") &&
        it->second["timings"].contains(metric))
      for (const auto& v : it->second["timings"][metric]) samples.push_back(v.get<double>());
    out.push_back(std::move(samples));
  }
  return out;
}

// The timed metrics both items of a pair have in the first run's samples.
std::set<std::string> shared_timings(const AaPair& pair, const RunView& run) {
  std::set<std::string> out;
  const auto a = run.samples.find(pair.original), b = run.samples.find(pair.copy);
  if (a == run.samples.end() || b == run.samples.end() || !a->second.is_object() ||
      !b->second.is_object() || !a->second.contains("timings") || !b->second.contains("timings"))
    return out;
  for (const auto& [metric, values] : a->second["timings"].items())
    if (b->second["timings"].contains(metric)) out.insert(metric);
  return out;
}

std::string percent_text(int part, int whole) {
  return significant_text(whole ? 100.0 * part / whole : 0.0, 2) + " %";
}

}  // namespace

bool is_aa_copy(const std::string& params) {
  return params_without_copy(params).second;
}

AaControls measure_aa_controls(const std::vector<RunView>& runs) {
  AaControls aa;
  if (runs.empty()) return aa;
  using Key = std::tuple<std::string, std::string, std::string, std::string>;
  std::map<Key, int> originals;
  std::vector<std::pair<Key, int>> copies;
  for (const auto& [index, rows] : runs[0].items) {
    if (rows.empty()) continue;
    const Row& r = *rows.front();
    const auto [params, copy] = params_without_copy(r.params);
    const Key key{r.experiment, r.scene, r.strategy, params};
    if (copy)
      copies.emplace_back(key, index);
    else
      originals.emplace(key, index);
  }
  for (const auto& [key, index] : copies)
    if (const auto it = originals.find(key); it != originals.end())
      aa.pairs.push_back({it->second, index});
  // Per metric: |log effect| of every A/A pair, and the intervals.
  std::map<std::string, std::vector<double>> spread;
  std::vector<std::pair<std::string, EffectInterval>> intervals;
  for (const AaPair& pair : aa.pairs)
    for (const std::string& metric : shared_timings(pair, runs[0])) {
      const RunInterval ri = run_interval({timings_of(pair.copy, metric, runs)},
                                          {timings_of(pair.original, metric, runs)});
      aa.runs = std::max(aa.runs, ri.runs);
      if (ri.runs < 2 || !ri.interval.ratio) continue;
      ++aa.tested;
      aa.outside += ri.interval.below() || ri.interval.above();
      spread[metric].push_back(std::abs(std::log(ri.interval.effect)));
      intervals.emplace_back(metric, ri.interval);
    }
  for (auto& [metric, values] : spread) {
    std::sort(values.begin(), values.end());
    const size_t rank = size_t(std::ceil(0.95 * double(values.size())));
    aa.tie_bands[metric] =
        std::max(kSmallestRatio, std::exp(values[std::max<size_t>(rank, 1) - 1]) - 1.0);
    aa.tested_by_metric[metric] = int(values.size());
  }
  for (auto& [metric, interval] : intervals) {
    interval.band = aa.tie_bands[metric];
    aa.outside_tie_band += interval.below() || interval.above();
  }
  return aa;
}

std::string aa_rate_text(const AaControls& aa) {
  if (aa.pairs.empty()) return "none (no experiment sets \"aa_duplicates\")";
  if (aa.tested == 0)
    return std::to_string(aa.pairs.size()) +
           " A/A pairs, no interval: they need timings in at least 2 runs";
  return std::to_string(aa.outside) + " of " + std::to_string(aa.tested) + " A/A intervals (" +
         percent_text(aa.outside, aa.tested) +
         ") exclude no effect (goal <= 5 %); with the tie bands from the A/A spread " +
         std::to_string(aa.outside_tie_band) + " of " + std::to_string(aa.tested) + " (" +
         percent_text(aa.outside_tie_band, aa.tested) + "); " + std::to_string(aa.pairs.size()) +
         " pairs, " + std::to_string(aa.runs) + " runs";
}

std::string tie_bands_text(const AaControls& aa) {
  std::string out;
  for (const auto& [metric, band] : aa.tie_bands)
    out += (out.empty() ? "" : ", ") + metric + " ±" + significant_text(100.0 * band, 2) + " % (" +
           std::to_string(aa.tested_by_metric.at(metric)) + " pairs)";
  return out.empty() ? "none measured" : out;
}

}  // namespace dv
