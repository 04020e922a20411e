// The advise run: search, front, verified pick (advise.h).
#include "experiments/advise/advise.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <utility>

#include "experiments/harness/interrupt.h"
#include "experiments/harness/scene_cache.h"
#include "experiments/harness/timing.h"

namespace dv {

namespace {

// Per round, the cheapest candidates verified at fresh points.
constexpr int kVerifyTries = 3;

std::string progress_line(const AdviseResult& r, size_t index) {
  char text[512];
  if (!r.measurement.ok)
    std::snprintf(text, sizeof text, "[%zu] %s: failed (%s)", index + 1,
                  r.config.param_line().c_str(), r.measurement.failure.c_str());
  else
    std::snprintf(text, sizeof text,
                  "[%zu] %s: p95 %.4g (%s), max %.3g, edge %.4f, %.3f ms, %.2f MB", index + 1,
                  r.config.param_line().c_str(), r.measurement.error_p95,
                  to_string(r.measurement.worst_stratum()), r.measurement.error_max,
                  r.measurement.image_edge, r.measurement.frame_ms, r.measurement.bytes / 1e6);
  return text;
}

// The final timing: the contenders timed again in interleaved rounds lead `candidates` in the
// order of their medians (one whose median breaks --budget-ms or that failed leaves), the other
// candidates follow as they were.
void time_contenders(AdviseMeasurer& measurer, const AdviseOptions& o,
                     std::vector<size_t>& candidates, Advice& advice) {
  const std::vector<size_t> contenders =
      timing_contenders(advice.results, candidates, kFinalTimingBand, kFinalTimingMost);
  if (contenders.size() < 2 || o.final_rounds < 1) return;
  if (o.progress)
    o.progress("final timing: " + std::to_string(contenders.size()) + " candidates in " +
               std::to_string(o.final_rounds) + " interleaved rounds");
  std::vector<ShadowConfig> configs;
  for (size_t i : contenders) configs.push_back(advice.results[i].config);
  const std::vector<std::vector<double>> times =
      measurer.interleaved_frame_ms(configs, o.final_rounds);
  for (size_t k = 0; k < contenders.size(); ++k)
    advice.final_timing.push_back({contenders[k], times[k], spread_of(times[k]).median});
  std::vector<Advice::FinalTiming> ranked = advice.final_timing;
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& a, const auto& b) { return a.median_ms < b.median_ms; });
  std::vector<size_t> order;
  for (const Advice::FinalTiming& t : ranked)
    if (std::isfinite(t.median_ms) && (!o.budgets.frame_ms || t.median_ms <= *o.budgets.frame_ms))
      order.push_back(t.index);
  order.insert(order.end(), candidates.begin() + std::ptrdiff_t(contenders.size()),
               candidates.end());
  candidates = std::move(order);
}

}  // namespace

ShadowConfig default_shadow_config() {
  return {"auto", {}};
}

double Advice::chosen_ms(size_t index) const {
  for (const FinalTiming& t : final_timing)
    if (t.index == index) return t.median_ms;
  return results[index].measurement.frame_ms;
}

std::vector<AdviseFamily> advise_space_for(const AdviseMeasurer& measurer, bool auto_only,
                                           int max_res) {
  std::vector<AdviseFamily> space = advise_space(measurer.kind());
  for (AdviseFamily& f : space)
    for (size_t a = 0; a < f.axes.size() && max_res > 0; ++a) {
      if (f.axes[a].key != "res") continue;
      std::vector<std::string>& v = f.axes[a].values;
      while (v.size() > 1 && std::stoi(v.back()) > max_res) v.pop_back();
      f.start[a] = std::min(f.start[a], int(v.size()) - 1);
    }
  if (!auto_only) return space;
  std::vector<AdviseFamily> out;
  for (AdviseFamily& f : space) {
    if (f.method == "shadowmap") {  // auto's depth maps take the dsm res and filter
      f.method = "auto";
      f.axes = {f.axes[0], {"filter", {"none", "bilinear"}}};
      out.push_back(f);
    } else if (f.method == "dsm") {
      f.method = "auto";
      out.push_back(f);
    }
  }
  return out;
}

Advice advise(SceneCache& cache, const AdviseOptions& o) {
  const auto begin = std::chrono::steady_clock::now();
  AdviseMeasurer measurer(cache, o.scene, o.settings);
  Advice advice;
  advice.light_count = measurer.light_count();
  advice.width = measurer.width();
  advice.height = measurer.height();
  advice.budgets = o.budgets;
  advice.strata_counts = measurer.strata(o.settings.seed).counts_text();
  if (o.progress)
    o.progress("probe strata (seed " + std::to_string(o.settings.seed) +
               "): " + advice.strata_counts);
  const bool measure_default = !o.speed_only && !o.budgets.image_error;
  const std::vector<AdviseFamily> space = advise_space_for(measurer, o.auto_only, o.max_res);
  AdviseSearchLimits limits;
  limits.max_evaluations = (o.exhaustive ? 1 << 20 : o.max_evaluations) - (measure_default ? 1 : 0);
  limits.stop = [] { return interrupt_requested(); };
  std::optional<AdviseResult> defaults;
  if (measure_default && limits.max_evaluations >= 0 && !interrupt_requested()) {
    defaults = AdviseResult{{-1, {}}, default_shadow_config(), {}};
    defaults->measurement = measurer.measure(defaults->config);
    if (defaults->measurement.ok) advice.budgets.image_error = defaults->measurement.image_edge;
  }
  const AdviseMeasure measure = [&](const ShadowConfig& c) { return measurer.measure(c); };
  const AdviseProgress progress = [&](const std::vector<AdviseResult>& results) {
    if (o.progress) o.progress(progress_line(results.back(), results.size() - 1));
  };
  std::vector<AdviseResult> searched =
      o.exhaustive ? advise_sweep(space, measure, limits, progress)
                   : advise_search(space, advice.budgets, measure, limits, progress);
  if (defaults && o.progress)
    o.progress(progress_line(*defaults, searched.size()) +
               " (the default: its image edge error bounds the pick's)");
  advice.verify_seed = o.settings.seed + kVerifySeedOffset;
  for (int round = 0;; ++round) {
    advice.results = searched;
    if (defaults) {
      advice.default_index = advice.results.size();
      advice.results.push_back(*defaults);
    }
    advice.front = advise_front(advice.results);
    std::vector<size_t> candidates = advise_picks(advice.results, advice.budgets);
    advice.final_timing.clear();
    if (!interrupt_requested()) time_contenders(measurer, o, candidates, advice);
    int tries = 0;
    for (size_t i : candidates) {
      if (tries++ == kVerifyTries || interrupt_requested()) break;
      advice.tried = i;
      advice.verified = measurer.verify(advice.results[i].config, advice.verify_seed);
      if (o.progress)
        o.progress("verify " + advice.results[i].config.param_line() + " at fresh points: p95 " +
                   std::to_string(advice.verified.error_p95) + " (" +
                   to_string(advice.verified.worst_stratum()) + ")");
      // The costs were budgeted in the search; the fresh points decide the error.
      if (advice.verified.ok && advice.budgets.within_error(advice.verified)) {
        advice.pick = i;
        break;
      }
      AdviseResult& rejected = i < searched.size() ? searched[i] : *defaults;
      rejected.measurement.add_fresh_points(advice.verified);
      advice.results[i].measurement = rejected.measurement;
    }
    if (advice.pick || tries == 0 || interrupt_requested() || round == kResumedRounds) break;
    if (o.exhaustive) continue;  // every point is measured: the next candidates are verified
    limits.max_evaluations = int(searched.size()) + kResumeEvaluations;
    if (o.progress)
      o.progress(
          "the fresh points rejected the cheapest candidates: the search resumes from "
          "the corrected front (" +
          std::to_string(kResumeEvaluations) + " more at most)");
    searched = advise_search(space, advice.budgets, measure, limits, progress, std::move(searched));
  }
  advice.front = advise_front(advice.results);
  advice.interrupted = interrupt_requested();
  if (advice.tried)
    advice.verified_strata_counts = measurer.strata(advice.verify_seed).counts_text();
  advice.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return advice;
}

}  // namespace dv
