// Timed shadow-method generation and timed raster frames (shadow_measure.h).
#include "experiments/harness/shadow_measure.h"

#include "cuda/pass_timer.h"
#include "experiments/harness/timing.h"

namespace dv {

double TimedGeneration::pass_milliseconds() const {
  return stats.contains("generation_ms") ? stats["generation_ms"].get<double>() : 0.0;
}

TimedGeneration timed_generation(const std::string& strategy, const StrategyParams& params,
                                 const SceneData& data, Backend backend, const Camera& camera) {
  TimedGeneration g;
  g.method = shadow_registry().create(strategy, params);
  PassTimer timer(backend);
  g.method->prepare(data, backend, &camera);
  g.milliseconds = timer.stop();
  g.stats = g.method->stats();
  return g;
}

TimedFrame timed_frame(Backend backend, const SceneData& data, const Camera& camera,
                       ShadowMethod& method, const dvec3& background, LooksKernel looks_kernel) {
  TimedFrame f;
  f.result = render_raster(backend, data, camera, method, background, {}, {}, looks_kernel);
  f.milliseconds = f.result.raster_ms + f.result.fragment_ms;
  return f;
}

double TimedRepeats::frame_ms() const {
  return spread_of(generate_ms).median + spread_of(render_ms).median;
}

TimedRepeats timed_repeats(const std::string& strategy, const StrategyParams& params,
                           const SceneData& data, Backend backend, const Camera& camera,
                           const dvec3& background, int repeat) {
  TimedRepeats t;
  for (int rep = 0; rep <= repeat; ++rep) {  // a fresh method each time, the first a warm-up
    t.last = timed_generation(strategy, params, data, backend, camera);
    if (rep == 0) continue;
    t.generate_ms.push_back(t.last.milliseconds);
    t.generate_stats.push_back(t.last.stats);
  }
  for (int rep = 0; rep <= repeat; ++rep) {
    TimedFrame frame = timed_frame(backend, data, camera, *t.last.method, background);
    t.frame = std::move(frame.result);
    if (rep == 0) continue;
    t.render_ms.push_back(frame.milliseconds);
    t.raster_ms.push_back(t.frame.raster_ms);
    t.fragment_ms.push_back(t.frame.fragment_ms);
  }
  return t;
}

double method_bytes(const nlohmann::json& stats) {
  if (stats.contains("storage") && stats["storage"].contains("bytes_allocated"))
    return stats["storage"]["bytes_allocated"].get<double>();
  double sum = 0.0;
  for (const auto& [key, v] : stats.items())
    if (v.is_number() &&
        (key == "bytes" || (key.size() > 6 && key.compare(key.size() - 6, 6, "_bytes") == 0)))
      sum += v.get<double>();
  return sum;
}

}  // namespace dv
