// Measuring a shadow configuration for `deepvox advise` (advise_measure.h).
#include "experiments/advise/advise_measure.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/error.h"
#include "experiments/harness/image_metrics.h"
#include "experiments/harness/shadow_measure.h"
#include "strategies/shadow/effect_planner.h"
#include "strategies/shadow/probe.h"

namespace dv {

namespace {

constexpr int kDefaultWidth = 320;

}  // namespace

AdviseMeasurer::AdviseMeasurer(SceneCache& cache, std::string scene_path, AdviseSettings s)
    : cache_(cache), path_(std::move(scene_path)), settings_(s) {
  const Camera& camera = cache_.scene(path_).camera;
  if (settings_.width <= 0) settings_.width = std::min(camera.width, kDefaultWidth);
  if (settings_.height <= 0)
    settings_.height = std::max(
        1, int(std::lround(double(settings_.width) * camera.height / std::max(camera.width, 1))));
  const SceneData& host = cache_.host_data(path_);
  for (int l = 0; l < int(host.host_lights().size()); ++l)
    casters_ = casters_ || !light_reach(host, l).casters.empty();
}

AdviseSceneKind AdviseMeasurer::kind() const {
  const SceneData& host = cache_.host_data(path_);
  AdviseSceneKind k;
  for (int l = 0; l < int(host.host_lights().size()); ++l) {
    const LightReach r = light_reach(host, l);
    k.translucent = k.translucent || r.translucent > 0;
    k.media = k.media || r.media > 0 || r.volumes > 0;
  }
  return k;
}

int AdviseMeasurer::light_count() const {
  return int(cache_.host_data(path_).host_lights().size());
}

const StratifiedProbes& AdviseMeasurer::strata(uint64_t seed) {
  return cache_.stratified_probes(path_, settings_.width, settings_.height,
                                  {settings_.probes, settings_.stratum_min, seed});
}

double AdviseMeasurer::oracle_ms() {
  return strata(settings_.seed).oracle_ms +
         cache_.reference(path_, settings_.width, settings_.height).milliseconds;
}

AdviseMeasurement AdviseMeasurer::measure(const ShadowConfig& config) {
  return measure_with(config, settings_.seed);
}

AdviseMeasurement AdviseMeasurer::verify(const ShadowConfig& config, uint64_t seed) {
  return measure_with(config, seed);
}

Camera AdviseMeasurer::camera() const {
  Camera camera = cache_.scene(path_).camera;
  camera.width = settings_.width;
  camera.height = settings_.height;
  return camera;
}

TimedRepeats AdviseMeasurer::timed(const ShadowConfig& config, const Camera& camera) {
  return timed_repeats(config.name, StrategyParams(config.params), cache_.data(path_),
                       cache_.backend(), camera, cache_.scene(path_).background, settings_.repeat);
}

std::vector<std::vector<double>> AdviseMeasurer::interleaved_frame_ms(
    const std::vector<ShadowConfig>& configs, int rounds) {
  const Camera view = camera();
  std::vector<std::vector<double>> times(configs.size());
  for (const std::vector<size_t>& round : interleaved_rounds(configs.size(), rounds))
    for (size_t k : round) {
      double ms = std::numeric_limits<double>::infinity();
      try {
        ms = timed(configs[k], view).frame_ms();
      } catch (const Error&) {  // as in measure_with: a failure is no time
      }
      times[k].push_back(ms);
    }
  return times;
}

AdviseMeasurement AdviseMeasurer::measure_with(const ShadowConfig& config, uint64_t seed) {
  AdviseMeasurement m;
  const SceneData& data = cache_.data(path_);
  const Camera view = camera();
  try {
    // The points and the oracle's answers (once per seed, cached) before the timed runs.
    const StratifiedProbes& probes = strata(seed);
    TimedRepeats repeats = timed(config, view);
    m.frame_ms = repeats.frame_ms();
    m.bytes = method_bytes(repeats.last.stats);
    ShadowMethod& method = *repeats.last.method;
    if (!probes.points.empty())
      m.strata = stratum_errors(
          probes,
          probe_transmittance(cache_.backend(), data, method, probes.points, &view).transmittance);
    m.error_p95 = worst_judged(m.strata);
    m.error_max = largest_error(m.strata);
    bool some_shadow = false;
    for (Stratum s : kAllStrata) {
      const StratumError& e = m.strata[size_t(s)];
      if (is_shadow(s)) {
        some_shadow = some_shadow || e.count > 0;
        m.shadows_measured = m.shadows_measured && !e.few;
      }
    }
    m.shadows_measured = m.shadows_measured && (some_shadow || !casters_);
    const ImageError image =
        image_error(repeats.frame.render.image,
                    cache_.reference(path_, settings_.width, settings_.height).image);
    m.image_rmse = image.rmse;
    m.image_edge = image.edge_error;
    m.ok = true;
  } catch (const Error& e) {  // a storage's limit, a backend it does not run on: not a pick
    m.ok = false;
    m.failure = e.what();
  }
  return m;
}

}  // namespace dv
