// Throughput of the exact transmittance oracle (and the reference renderer) on the committed
// scenes, per backend: what a per-image ground truth costs. Google Benchmark with manual time
// (synchronised wall time of the query kernel alone; CUDA runs are synchronised before the
// clock stops). Run: build/bin/bench_oracle --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <random>
#include <string>

#include "cuda/device_memory.h"
#include "experiments/source_paths.h"
#include "render/frame/reference_render.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/probe.h"

namespace dv {
namespace {

std::string scene_path(const char* name) {
  return test::source_dir() + "/experiments/scenes/" + name;
}

std::vector<dvec3> random_points(const Scene& scene, int n) {
  const Aabb b = world_bounds(scene);
  std::mt19937 rng(11);
  std::vector<dvec3> pts(n);
  for (dvec3& p : pts)
    for (int a = 0; a < 3; ++a)
      p[a] = std::uniform_real_distribution<double>(b.lo[a], b.hi[a])(rng);
  return pts;
}

void probe(benchmark::State& state, const char* scene_name, Backend backend) {
  std::string why;
  if (backend == Backend::cuda && !cuda_device_available(&why))
    return state.SkipWithError(why.c_str());
  const Scene scene = load_scene(scene_path(scene_name));
  const SceneData data(scene, memory_of(backend));
  const std::vector<dvec3> points = random_points(scene, int(state.range(0)));
  auto method = shadow_registry().create("reference");
  probe_transmittance(backend, data, *method, points);  // warm-up
  for (auto _ : state)
    state.SetIterationTime(probe_transmittance(backend, data, *method, points).milliseconds / 1e3);
  state.SetItemsProcessed(state.iterations() * state.range(0) * int64_t(scene.lights.size()));
  state.SetLabel(backend == Backend::cuda ? cuda_device_name() : "cpu");
}

void render(benchmark::State& state, const char* scene_name, Backend backend) {
  std::string why;
  if (backend == Backend::cuda && !cuda_device_available(&why))
    return state.SkipWithError(why.c_str());
  const Scene scene = load_scene(scene_path(scene_name));
  const SceneData data(scene, memory_of(backend));
  auto method = shadow_registry().create("reference");
  render_reference(backend, data, scene.camera, *method, scene.background);  // warm-up
  for (auto _ : state)
    state.SetIterationTime(
        render_reference(backend, data, scene.camera, *method, scene.background).milliseconds /
        1e3);
  state.SetLabel(backend == Backend::cuda ? cuda_device_name() : "cpu");
}

BENCHMARK_CAPTURE(probe, demo_cpu, "demo.json", Backend::cpu)
    ->Arg(1 << 14)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(probe, demo_cuda, "demo.json", Backend::cuda)
    ->Arg(1 << 20)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(probe, ct_cpu, "ct-phantom.json", Backend::cpu)
    ->Arg(1 << 12)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(probe, ct_cuda, "ct-phantom.json", Backend::cuda)
    ->Arg(1 << 18)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render, demo_cpu, "demo.json", Backend::cpu)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(render, demo_cuda, "demo.json", Backend::cuda)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render, ct_cuda, "ct-phantom.json", Backend::cuda)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dv

BENCHMARK_MAIN();
