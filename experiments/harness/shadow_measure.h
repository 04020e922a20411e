// The shadow measurements themselves, shared by the suite's `shadow` driver (which repeats them
// after a warm-up and writes rows) and the Google Benchmark programs bench_dsm and
// bench_renderer (which let the benchmark library repeat them), so no measurement exists in
// two copies: a generation is a fresh method prepared for a camera, timed around prepare; a
// frame is the raster renderer's binning plus fragment pass with that method's shadows. The
// repeated form (timed_repeats: a warm-up, then timed repetitions) serves the suite's driver and
// `deepvox advise` alike, with the canonical memory figure (method_bytes).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "render/frame/raster_render.h"
#include "strategies/shadow/shadow_method.h"

namespace dv {

struct TimedGeneration {
  std::unique_ptr<ShadowMethod> method;
  double milliseconds = 0.0;  // PassTimer around prepare (synchronised on CUDA)
  nlohmann::json stats;       // the method's stats after prepare (per-pass times, storage)
  // The method's own sum of its timed passes ("generation_ms", CUDA events per pass); 0 for
  // methods that report none.
  double pass_milliseconds() const;
};

// A fresh method `strategy` with `params` from the shadow registry, prepared on `data` (in the
// memory of `backend`) for `camera`.
TimedGeneration timed_generation(const std::string& strategy, const StrategyParams& params,
                                 const SceneData& data, Backend backend, const Camera& camera);

struct TimedFrame {
  RasterRenderResult result;
  double milliseconds = 0.0;  // raster_ms + fragment_ms
};

// One frame of the raster renderer with `method`'s shadows (prepared already, or by the
// renderer on its first frame).
TimedFrame timed_frame(Backend backend, const SceneData& data, const Camera& camera,
                       ShadowMethod& method, const dvec3& background,
                       LooksKernel looks_kernel = LooksKernel::fitted);

// One warm-up and `repeat` timed repetitions of a fresh generation, then one warm-up and
// `repeat` timed frames with the last generation's method.
struct TimedRepeats {
  std::vector<double> generate_ms, render_ms, raster_ms, fragment_ms;  // per timed repetition
  std::vector<nlohmann::json> generate_stats;                          // likewise
  TimedGeneration last;      // the last generation, its method prepared
  RasterRenderResult frame;  // the last frame
  double frame_ms() const;   // median generation + median render: the Pareto fronts' time
};
TimedRepeats timed_repeats(const std::string& strategy, const StrategyParams& params,
                           const SceneData& data, Backend backend, const Camera& camera,
                           const dvec3& background, int repeat);

// The canonical memory figure of a method's stats: the DSM storage's bytes allocated, else the
// method's "bytes" and "*_bytes" figures summed (0 for methods that keep nothing).
double method_bytes(const nlohmann::json& stats);

}  // namespace dv
