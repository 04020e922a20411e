// The advise run: search, front, verified pick (advise.h).
#include "experiments/harness/advise.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "experiments/harness/interrupt.h"
#include "experiments/harness/scene_cache.h"

namespace dv {

namespace {

constexpr int kVerifyTries = 3;

std::string progress_line(const AdviseResult& r, size_t index) {
  char text[256];
  if (!r.measurement.ok)
    std::snprintf(text, sizeof text, "[%zu] %s: failed (%s)", index + 1,
                  r.config.param_line().c_str(), r.measurement.failure.c_str());
  else
    std::snprintf(text, sizeof text, "[%zu] %s: p95 %.4g, max %.3g, %.3f ms, %.2f MB", index + 1,
                  r.config.param_line().c_str(), r.measurement.error_p95, r.measurement.error_max,
                  r.measurement.frame_ms, r.measurement.bytes / 1e6);
  return text;
}

}  // namespace

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
  const std::vector<AdviseFamily> space = advise_space_for(measurer, o.auto_only, o.max_res);
  AdviseSearchLimits limits;
  limits.max_evaluations = o.exhaustive ? 1 << 20 : o.max_evaluations;
  limits.stop = [] { return interrupt_requested(); };
  const AdviseMeasure measure = [&](const ShadowConfig& c) { return measurer.measure(c); };
  const AdviseProgress progress = [&](const std::vector<AdviseResult>& results) {
    if (o.progress) o.progress(progress_line(results.back(), results.size() - 1));
  };
  advice.results = o.exhaustive ? advise_sweep(space, measure, limits, progress)
                                : advise_search(space, o.budgets, measure, limits, progress);
  advice.interrupted = interrupt_requested();
  advice.front = advise_front(advice.results);
  advice.verify_seed = o.settings.seed + kVerifySeedOffset;
  int tries = 0;
  for (size_t i : advise_picks(advice.results, o.budgets)) {
    if (tries++ == kVerifyTries || interrupt_requested()) break;
    advice.tried = i;
    advice.verified = measurer.verify(advice.results[i].config, advice.verify_seed);
    if (o.progress)
      o.progress("verify " + advice.results[i].config.param_line() + " at fresh points: p95 " +
                 std::to_string(advice.verified.error_p95));
    // The costs were budgeted in the search; the fresh points decide the error.
    if (advice.verified.ok && advice.verified.error_p95 <= o.budgets.error) {
      advice.pick = i;
      break;
    }
  }
  advice.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return advice;
}

}  // namespace dv
