// Google Benchmark cases over the suite's own frame measurement (experiments/harness/
// shadow_measure.h, which the `seeds` experiment no-shadow-baseline runs too): the rasterizing
// renderer on experiments/scenes/knecht-fig56.json (one spot light, two 128^3 volumes, six
// polyhedra, 720x480, step 0.5 voxel), tile binning and the fragment pass (gather, sort, walk,
// shade) timed separately with CUDA events on the GPU, per shadow method (the method generated once
// before). Knecht 2011 reports 43 ms without shadows on a GTX 480. Bandwidth floor
// (bandwidth_floor.h): fragment_floor_ms is the image written once over the device copy bandwidth
// measured in the run (copy_GBps), fragment_floor_x the pass's multiple; raster_floor_ms /
// raster_floor_x the same for the tile binning (the scene read, the lists written). With
// DEEPVOX_KERNEL_TIMING=1 each case adds a counter per kernel (experiments/kernel_counters.h). Run:
// build/bin/bench_renderer --benchmark_repetitions=5. The goal/ cases time the project's frame
// goals at their image sizes (goal_ms beside the time).
#include <benchmark/benchmark.h>

#include <chrono>
#include <string>

#include "cuda/device_memory.h"
#include "engine/raster/tile_raster.h"
#include "experiments/bandwidth_floor.h"
#include "experiments/harness/shadow_measure.h"
#include "experiments/kernel_counters.h"
#include "experiments/source_paths.h"
#include "render/load/scene_loader.h"

namespace dv {
namespace {

// One measured frame: the scene (under experiments/scenes/), the shadow method and its
// parameters, the image size (0: the scene camera's) and, for the goal cases, the frame time the
// project aims at (goal_ms, 0: none; the case then reports goal_x = frame time / goal).
struct FrameCase {
  const char* scene;
  const char* shadows;
  const char* params = "";
  int width = 0, height = 0;
  double goal_ms = 0.0;
  LooksKernel looks_kernel = LooksKernel::fitted;
};

void raster_render_case(benchmark::State& state, const FrameCase& c, Backend backend) {
  std::string why;
  if (backend == Backend::cuda && !cuda_device_available(&why))
    return state.SkipWithError(why.c_str());
  Scene scene = load_scene(test::source_dir() + "/experiments/scenes/" + c.scene);
  if (c.width > 0) scene.camera.width = c.width, scene.camera.height = c.height;
  const SceneData data(scene, memory_of(backend));
  const StrategyParams params = *c.params ? StrategyParams::parse({c.params}) : StrategyParams{};
  const TimedGeneration g = timed_generation(c.shadows, params, data, backend, scene.camera);
  timed_frame(backend, data, scene.camera, *g.method, scene.background, c.looks_kernel);  // warm-up
  double raster_ms = 0.0, fragment_ms = 0.0;
  OracleFrameStats oracle;  // the deferred oracle pass's parts, summed over the iterations
  int64_t entries = 0;
  start_kernel_counters();
  for (auto _ : state) {
    const TimedFrame f =
        timed_frame(backend, data, scene.camera, *g.method, scene.background, c.looks_kernel);
    state.SetIterationTime(f.milliseconds / 1e3);
    raster_ms += f.result.raster_ms;
    entries = f.result.raster.entries;
    fragment_ms += f.result.fragment_ms;
    oracle.queries = f.result.render.oracle.queries;
    oracle.count_ms += f.result.render.oracle.count_ms;
    oracle.record_ms += f.result.render.oracle.record_ms;
    oracle.answer_ms += f.result.render.oracle.answer_ms;
    oracle.replay_ms += f.result.render.oracle.replay_ms;
  }
  add_kernel_counters(state);
  const double iterations = double(state.iterations());
  state.counters["raster_ms"] = raster_ms / iterations;
  state.counters["fragment_ms"] = fragment_ms / iterations;
  if (oracle.queries > 0) {
    state.counters["oracle_queries"] = double(oracle.queries);
    state.counters["oracle_count_ms"] = oracle.count_ms / iterations;
    state.counters["oracle_record_ms"] = oracle.record_ms / iterations;
    state.counters["oracle_answer_ms"] = oracle.answer_ms / iterations;
    state.counters["oracle_replay_ms"] = oracle.replay_ms / iterations;
  }
  if (backend == Backend::cuda) {
    static const double bytes_per_ms = measure_copy_bandwidth();
    const double floor_ms =
        frame_floor_bytes(scene.camera.width, scene.camera.height) / bytes_per_ms;
    state.counters["copy_GBps"] = bytes_per_ms / 1e6;
    state.counters["fragment_floor_ms"] = floor_ms;
    state.counters["fragment_floor_x"] = state.counters["fragment_ms"] / floor_ms;
    const int64_t tiles =
        int64_t(tiles_along(scene.camera.width)) * tiles_along(scene.camera.height);
    const double raster_floor_ms =
        tile_binning_floor_bytes(data.view().triangles.size, data.view().vertices.size, 1, entries,
                                 tiles) /
        bytes_per_ms;
    state.counters["raster_floor_ms"] = raster_floor_ms;
    state.counters["raster_floor_x"] = state.counters["raster_ms"] / raster_floor_ms;
  }
  state.counters["generate_ms"] = g.milliseconds;
  if (c.goal_ms > 0.0) {
    state.counters["goal_ms"] = c.goal_ms;
    state.counters["goal_x"] =
        state.counters["fragment_ms"] / c.goal_ms + state.counters["raster_ms"] / c.goal_ms;
  }
  state.SetLabel(backend == Backend::cuda ? cuda_device_name() : "cpu");
}

void raster_render(benchmark::State& state, const char* scene_name, const char* shadows,
                   Backend backend) {
  raster_render_case(state, FrameCase{scene_name, shadows}, backend);
}

// The frame-time goals of the oracle and the 4K camera pass (one light, knecht-fig56) and of many
// lights (knecht-32-lights, 112 map faces), on CUDA: goal_x > 1 is a goal missed by that factor.
// Run: build/bin/bench_renderer --benchmark_filter=goal/ --benchmark_repetitions=5
const FrameCase kFrameGoals[] = {
    {"knecht-fig56.json", "reference", "", 0, 0, 15.0},
    {"knecht-fig56.json", "reference", "", 1920, 1080, 40.0},
    {"knecht-32-lights.json", "reference", "", 0, 0, 500.0},
    {"knecht-fig56.json", "none", "", 3840, 2160, 2.5},
    {"knecht-fig56.json", "shadowmap", "", 3840, 2160, 3.0},
    {"knecht-fig56.json", "dsm", "res=1024", 3840, 2160, 4.0},
    {"knecht-fig56.json", "none", "", 1920, 1080, 0.8},
    {"knecht-fig56.json", "dsm", "res=1024", 1920, 1080, 1.2},
    {"knecht-fig56.json", "none", "", 0, 0, 0.868},
    {"knecht-fig56.json", "shadowmap", "", 0, 0, 1.05},
    {"knecht-32-lights.json", "dsm", "res=512", 0, 0, 2.0},
    {"knecht-32-lights.json", "dsm", "res=512", 1920, 1080, 5.0},
    {"knecht-32-lights.json", "dsm", "res=512", 3840, 2160, 16.7},
    {"knecht-32-lights.json", "shadowmap", "", 3840, 2160, 12.0},
};

[[maybe_unused]] const bool kFrameGoalsRegistered = [] {
  for (const FrameCase& c : kFrameGoals) {
    const std::string scene = std::string(c.scene).substr(0, std::string(c.scene).find('.'));
    const std::string size = c.width > 0 ? std::to_string(c.width) + "x" + std::to_string(c.height)
                                         : std::string("scene");
    const std::string name = "goal/" + scene + "/" + c.shadows +
                             (*c.params ? std::string("_") + c.params : std::string()) + "/" +
                             size + "/cuda";
    benchmark::RegisterBenchmark(name.c_str(), raster_render_case, c, Backend::cuda)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(std::string(c.shadows) == "reference" ? 3 : 20);
  }
  return true;
}();

// One frame per feature path, so that a change shows what each path costs and that a scene
// without a feature does not pay for it: a grey untextured scene with neither media nor glass
// (translucent-boxes), the same boxes in smoke (a volume), a red glass slab (transmission and
// coloured shadows), tinted glass around a constant medium, and a textured glTF; each at
// 720x480 without shadows, with a shadow map and with a dsm (compact, 1024^2).
const char* const kFeatureScenes[] = {"translucent-boxes.json", "smoke-translucent-boxes.json",
                                      "glass-red-slab.json", "glass-tinted-medium.json",
                                      "../assets/gltf/textured-torus.gltf"};
const char* const kFeatureShadows[] = {"none", "shadowmap", "dsm"};

[[maybe_unused]] const bool kFeaturePathsRegistered = [] {
  for (const char* scene_file : kFeatureScenes) {
    const std::string file = scene_file;
    const size_t slash = file.find_last_of('/') + 1;  // 0 when there is none
    const std::string scene = file.substr(slash, file.find('.', slash) - slash);
    for (const char* shadows : kFeatureShadows) {
      const std::string name = "feature/" + scene + "/" + shadows + "/720x480/cuda";
      benchmark::RegisterBenchmark(name.c_str(), raster_render_case,
                                   FrameCase{scene_file, shadows, "", 720, 480}, Backend::cuda)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond)
          ->Iterations(20);
    }
  }
  return true;
}();

// What the camera pass's kernel for plain surface looks saves (render/frame/shade_payload.h): grey
// scenes (every surface untextured, without glass, not emitting) with that kernel (fitted) and with
// the general one every other scene runs, in one binary; 720x480 without shadows, with a shadow map
// and with a dsm (compact, 1024^2).
[[maybe_unused]] const bool kLooksKernelsRegistered = [] {
  for (const char* scene_file : {"knecht-fig56.json", "translucent-boxes.json"})
    for (const char* shadows : kFeatureShadows)
      for (const LooksKernel kernel : {LooksKernel::fitted, LooksKernel::general}) {
        const std::string file = scene_file;
        const std::string name = "looks/" + file.substr(0, file.find('.')) + "/" + shadows + "/" +
                                 (kernel == LooksKernel::fitted ? "fitted" : "general") +
                                 "/720x480/cuda";
        FrameCase c{scene_file, shadows, "", 720, 480};
        c.looks_kernel = kernel;
        benchmark::RegisterBenchmark(name.c_str(), raster_render_case, c, Backend::cuda)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond)
            ->Iterations(20);
      }
  return true;
}();

BENCHMARK_CAPTURE(raster_render, fig56_none_cuda, "knecht-fig56.json", "none", Backend::cuda)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(raster_render, fig56_shadowmap_cuda, "knecht-fig56.json", "shadowmap",
                  Backend::cuda)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(raster_render, fig56_reference_cuda, "knecht-fig56.json", "reference",
                  Backend::cuda)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(raster_render, fig56_none_cpu, "knecht-fig56.json", "none", Backend::cpu)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);

// The effect planner's saving (experiments/scenes/knecht-planner.json: the Knecht-like scene's
// volumes and translucent objects under its spot light, plus four spot lights that reach only
// opaque objects and one that reaches nothing): `auto` against `dsm` for every light. "first" times
// a frame with a fresh method (maps built: what an edited scene or a new light costs), "steady" a
// frame with the maps cached. Wall clock around the whole frame (map builds included).
// Run: build/bin/bench_renderer --benchmark_filter=planner
void planned_frame(benchmark::State& state, const char* shadows, const char* params,
                   bool fresh_maps, Backend backend) {
  std::string why;
  if (backend == Backend::cuda && !cuda_device_available(&why))
    return state.SkipWithError(why.c_str());
  const Scene scene = load_scene(test::source_dir() + "/experiments/scenes/knecht-planner.json");
  const SceneData data(scene, memory_of(backend));
  const auto make = [&] {
    return shadow_registry().create(shadows, StrategyParams::parse({params}));
  };
  auto method = make();
  render_raster(backend, data, scene.camera, *method, scene.background);  // warm-up
  for (auto _ : state) {
    if (fresh_maps) method = make();
    const auto start = std::chrono::steady_clock::now();
    render_raster(backend, data, scene.camera, *method, scene.background);
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  state.counters["maps_built"] = method->stats().value("maps_built", 0);
  int deep = 0, depth = 0;  // lights with a deep map, with a depth map (auto's plan)
  const nlohmann::json plan = method->plan();
  for (const nlohmann::json& l : plan.is_null() ? nlohmann::json::array() : plan["lights"]) {
    deep += l["method"] == "dsm";
    depth += l["method"] == "shadowmap";
  }
  state.counters["deep_map_lights"] = plan.is_null() ? double(data.host_lights().size()) : deep;
  state.counters["depth_map_lights"] = depth;
  state.SetLabel(backend == Backend::cuda ? cuda_device_name() : "cpu");
}

BENCHMARK_CAPTURE(planned_frame, planner_first_auto_cuda, "auto", "res=1024", true, Backend::cuda)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(planned_frame, planner_first_dsm_cuda, "dsm", "res=1024", true, Backend::cuda)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(planned_frame, planner_steady_auto_cuda, "auto", "res=1024", false, Backend::cuda)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(planned_frame, planner_steady_dsm_cuda, "dsm", "res=1024", false, Backend::cuda)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(planned_frame, planner_first_auto_cpu, "auto", "res=256", true, Backend::cpu)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);
BENCHMARK_CAPTURE(planned_frame, planner_first_dsm_cpu, "dsm", "res=256", true, Backend::cpu)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);
BENCHMARK_CAPTURE(planned_frame, planner_steady_auto_cpu, "auto", "res=256", false, Backend::cpu)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);
BENCHMARK_CAPTURE(planned_frame, planner_steady_dsm_cpu, "dsm", "res=256", false, Backend::cpu)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);

}  // namespace
}  // namespace dv

BENCHMARK_MAIN();
