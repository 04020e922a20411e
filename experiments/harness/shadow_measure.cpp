// Timed shadow-method generation and timed raster frames (shadow_measure.h).
#include "experiments/harness/shadow_measure.h"

#include "cuda/pass_timer.h"

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
                       ShadowMethod& method, const dvec3& background) {
  TimedFrame f;
  f.result = render_raster(backend, data, camera, method, background);
  f.milliseconds = f.result.raster_ms + f.result.fragment_ms;
  return f;
}

}  // namespace dv
