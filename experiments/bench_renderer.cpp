// Google Benchmark cases over the suite's own frame measurement (experiments/harness/
// shadow_measure.h, which the `seeds` experiment no-shadow-baseline runs too): the rasterizing
// renderer on scenes/knecht-fig56.json (one spot light, two 128^3 volumes, six polyhedra,
// 720x480, step 0.5 voxel), tile binning and the fragment pass (gather, sort, walk, shade) timed
// separately with CUDA events on the GPU, per shadow method (the method generated once before).
// Knecht 2011 reports 43 ms without shadows on a GTX 480.
// Run: build/bin/bench_renderer --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <string>

#include "cuda/device_memory.h"
#include "experiments/harness/shadow_measure.h"
#include "load/scene_loader.h"
#include "tests/support/paths.h"

namespace dv {
namespace {

void raster_render(benchmark::State& state, const char* scene_name, const char* shadows,
                   Backend backend) {
  std::string why;
  if (backend == Backend::cuda && !cuda_device_available(&why))
    return state.SkipWithError(why.c_str());
  const Scene scene = load_scene(test::source_dir() + "/scenes/" + scene_name);
  const SceneData data(scene, memory_of(backend));
  const TimedGeneration g = timed_generation(shadows, {}, data, backend, scene.camera);
  timed_frame(backend, data, scene.camera, *g.method, scene.background);  // warm-up
  double raster_ms = 0.0, fragment_ms = 0.0;
  for (auto _ : state) {
    const TimedFrame f = timed_frame(backend, data, scene.camera, *g.method, scene.background);
    state.SetIterationTime(f.milliseconds / 1e3);
    raster_ms += f.result.raster_ms;
    fragment_ms += f.result.fragment_ms;
  }
  state.counters["raster_ms"] = raster_ms / double(state.iterations());
  state.counters["fragment_ms"] = fragment_ms / double(state.iterations());
  state.SetLabel(backend == Backend::cuda ? cuda_device_name() : "cpu");
}

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

}  // namespace
}  // namespace dv

BENCHMARK_MAIN();
