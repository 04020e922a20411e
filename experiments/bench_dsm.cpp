// Deep-shadow-map benchmarks on experiments/scenes/knecht-fig56.json (one spot light, two 128^3
// volumes, six polyhedra, 720x480), eps 0.05, per storage strategy, on the GPU with CUDA events.
// generate/<storage>/cuda at 256^2, 512^2, 1024^2: the iteration time is a regeneration of the
// same maps in place (DeepShadowMaps::generate after a warm-up: allocations and first touch
// done; the sum of its passes: light-view rasterization, counting, scan, writes, re-layout), what
// an animated scene pays per frame and what no suite measures; fresh_pass_ms and fresh_wall_ms
// are the suite's own measurement of a first generation (experiments/harness/shadow_measure.h,
// the seeds experiment dsm-resolution's generate.generation_ms and generate_ms), called, not
// copied; wall_ms is the regeneration's wall clock on the host (passes, the host work between
// them and the figures' read-back); records_copy_ms the copy of the per-texel records to the
// host that each generation made until the figures were summed on the device. Counters: every
// pass, the memory figures and Knecht 2011 §5.8's formulas (texture3d d^2 * 64 layers * 64 bit,
// chunked nodes * 128 bit + d^2 * 64 bit).
// render_bilinear: the bilinear-filtered frame per storage through the harness's timed frame (the
// suite's render_ms). lights32: every light's maps of experiments/scenes/knecht-32-lights.json plus
// one bilinear frame (no suite runs it), through the same harness functions. Bandwidth floor
// (bandwidth_floor.h): copy_GBps measured once in the run; per modelled generation pass
// PASS_floor_ms (its fewest bytes over that bandwidth; raster: the scene read per light view,
// the tile lists written, while its time is all of DsmGeneration's set-up: faces, uploads, the
// tile binning, the ray media) and PASS_floor_x = PASS_ms / floor_ms.
// With DEEPVOX_KERNEL_TIMING=1 the generate and render_bilinear cases add a counter per kernel
// (experiments/kernel_counters.h).
// Run: build/bin/bench_dsm --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "cuda/device_memory.h"
#include "engine/raster/tile_raster.h"
#include "experiments/bandwidth_floor.h"
#include "experiments/harness/shadow_measure.h"
#include "experiments/kernel_counters.h"
#include "experiments/source_paths.h"
#include "render/load/scene_loader.h"
#include "strategies/storage/deep_shadow_maps.h"

namespace dv {
namespace {

const Scene& fig56() {
  static const Scene scene =
      load_scene(test::source_dir() + "/experiments/scenes/knecht-fig56.json");
  return scene;
}

// "chunked:alloc=thesis" -> storage=chunked storage.alloc=thesis, plus the given items.
StrategyParams dsm_params(const std::string& storage, std::vector<std::string> items) {
  const size_t colon = storage.find(':');
  items.push_back("storage=" + storage.substr(0, colon));
  if (colon != std::string::npos) items.push_back("storage." + storage.substr(colon + 1));
  return StrategyParams::parse(items);
}

bool skip_without_device(benchmark::State& state, Backend backend) {
  std::string why;
  if (backend != Backend::cuda || cuda_device_available(&why)) return false;
  state.SkipWithError(why.c_str());
  return true;
}

// The storage's memory figures beside Knecht's formulas, and every pass of the last generation.
void report_figures(benchmark::State& state, const DeepShadowMaps& maps, const SceneData& scene,
                    Backend backend) {
  const nlohmann::json& f = maps.figures();
  const double d2 = double(maps.settings().resolution) * maps.settings().resolution;
  state.counters["MB_allocated"] = f["bytes_allocated"].get<double>() / 1e6;
  state.counters["MB_in_nodes"] = f["bytes_in_nodes"].get<double>() / 1e6;
  state.counters["nodes"] = f["nodes"].get<double>();
  state.counters["mean_layers"] = f["mean_layers"].get<double>();
  state.counters["max_layers"] = f["max_layers"].get<double>();
  state.counters["overflowed"] = f["overflowed_texels"].get<double>();
  state.counters["knecht_tex3d_MB"] = d2 * 64.0 * 8.0 / 1e6;
  state.counters["knecht_chunked_MB"] = (f["nodes"].get<double>() * 16.0 + d2 * 8.0) / 1e6;
  const nlohmann::json& own = f["strategy"];
  if (own.contains("chunks_wasted")) {
    state.counters["chunks_used"] = own["chunks_used"].get<double>();
    state.counters["chunks_wasted"] = own["chunks_wasted"].get<double>();
  }
  for (const DsmPass& p : maps.passes()) state.counters[p.name + "_ms"] = p.milliseconds;
  if (backend != Backend::cuda) return;
  const int views = int(maps.layout().faces.size());
  const int64_t tiles_per_view =
      int64_t(tiles_along(maps.resolution())) * tiles_along(maps.resolution());
  const DsmFloorInputs floor{
      f["texels"].get<int64_t>(), f["bytes_in_nodes"].get<double>(),
      tile_binning_floor_bytes(scene.view().triangles.size, scene.view().vertices.size, views,
                               maps.fragments(), views * tiles_per_view)};
  static const double bytes_per_ms = measure_copy_bandwidth();
  state.counters["copy_GBps"] = bytes_per_ms / 1e6;
  for (const DsmPass& p : maps.passes()) {
    const std::optional<double> bytes = dsm_pass_floor_bytes(p.name, floor);
    if (!bytes) continue;
    state.counters[p.name + "_floor_ms"] = *bytes / bytes_per_ms;
    state.counters[p.name + "_floor_x"] = p.milliseconds / (*bytes / bytes_per_ms);
  }
}

void dsm_generate(benchmark::State& state, std::string storage, Backend backend) {
  if (skip_without_device(state, backend)) return;
  const Scene& scene = fig56();
  const SceneData data(scene, memory_of(backend));
  const int res = int(state.range(0));
  const TimedGeneration fresh =
      timed_generation("dsm", dsm_params(storage, {"res=" + std::to_string(res), "eps=0.05"}), data,
                       backend, scene.camera);
  DeepShadowMaps maps(fresh.method->deep_shadow_maps()->settings());
  maps.generate(data, backend);  // warm-up: allocations, first touch
  double wall_ms = 0.0;
  start_kernel_counters();
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    maps.generate(data, backend);
    wall_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    state.SetIterationTime(maps.generation_milliseconds() / 1e3);
  }
  add_kernel_counters(state);
  state.counters["wall_ms"] = wall_ms / double(state.iterations());
  const auto copy_start = std::chrono::steady_clock::now();
  maps.records();  // the host copy every generation made before figures() summed on the device
  state.counters["records_copy_ms"] =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - copy_start)
          .count();
  state.counters["fresh_pass_ms"] = fresh.pass_milliseconds();
  state.counters["fresh_wall_ms"] = fresh.milliseconds;
  report_figures(state, maps, data, backend);
  state.SetLabel(backend == Backend::cuda ? cuda_device_name() : "cpu");
}

void dsm_render(benchmark::State& state, std::string storage) {
  if (skip_without_device(state, Backend::cuda)) return;
  const Scene& scene = fig56();
  const SceneData data(scene, Memory::device);
  const TimedGeneration g = timed_generation(
      "dsm",
      dsm_params(storage, {"res=" + std::to_string(state.range(0)), "eps=0.05", "filter=bilinear"}),
      data, Backend::cuda, scene.camera);
  timed_frame(Backend::cuda, data, scene.camera, *g.method, scene.background);  // warm-up
  double fragment_ms = 0.0;
  start_kernel_counters();
  for (auto _ : state) {
    const TimedFrame f =
        timed_frame(Backend::cuda, data, scene.camera, *g.method, scene.background);
    state.SetIterationTime(f.milliseconds / 1e3);
    fragment_ms += f.result.fragment_ms;
  }
  add_kernel_counters(state);
  state.counters["fragment_ms"] = fragment_ms / double(state.iterations());
  state.counters["maps_built"] = g.method->stats()["maps_built"].get<double>();
  state.SetLabel(cuda_device_name());
}

// experiments/scenes/knecht-32-lights.json (the same objects under 16 spot and 16 omni lights):
// maps of every light generated, then one rasterized frame with bilinear lookups of all 32 lights;
// range(0) = res, range(1) = clusters. On the CPU at a small image and resolution so it runs
// anywhere; on CUDA at the scene's image size.
void many_lights(benchmark::State& state, Backend backend) {
  if (skip_without_device(state, backend)) return;
  static const Scene many =
      load_scene(test::source_dir() + "/experiments/scenes/knecht-32-lights.json");
  Scene scene = many;
  if (backend == Backend::cpu) scene.camera.width = 120, scene.camera.height = 80;
  const SceneData data(scene, memory_of(backend));
  const StrategyParams params = StrategyParams::parse({"res=" + std::to_string(state.range(0)),
                                                       "clusters=" + std::to_string(state.range(1)),
                                                       "eps=0.05", "filter=bilinear"});
  double generation_ms = 0.0, fragment_ms = 0.0;
  for (auto _ : state) {
    const TimedGeneration g = timed_generation("dsm", params, data, backend, scene.camera);
    const TimedFrame f = timed_frame(backend, data, scene.camera, *g.method, scene.background);
    generation_ms += g.pass_milliseconds();
    fragment_ms += f.result.fragment_ms;
    state.SetIterationTime((g.pass_milliseconds() + f.milliseconds) / 1e3);
    state.counters["maps"] = g.stats["faces"].get<double>();
    // The maps' bytes (the goal: 112 maps of 512^2 in <= 300 MB) and the per-texel
    // records held beside them.
    state.counters["storage_mb"] = g.stats["storage"]["bytes_allocated"].get<double>() / 1e6;
    state.counters["records_mb"] =
        g.stats["storage"]["texels"].get<double>() * double(sizeof(DsmTexelRecord)) / 1e6;
  }
  state.counters["lights"] = double(scene.lights.size());
  state.counters["generation_ms"] = generation_ms / double(state.iterations());
  state.counters["fragment_ms"] = fragment_ms / double(state.iterations());
  state.SetLabel(backend == Backend::cuda ? cuda_device_name() : "cpu");
}

void register_all() {
  benchmark::RegisterBenchmark("lights32/cpu", many_lights, Backend::cpu)
      ->Args({64, 1})
      ->Args({64, 4})
      ->Iterations(1)
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("lights32/cuda", many_lights, Backend::cuda)
      ->Args({512, 1})
      ->Args({1024, 4})
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond);
  // Every registered storage (a new one is benchmarked with no edit here), plus the thesis's
  // racing chunk allocation.
  std::vector<std::string> storages = storage_registry().names();
  storages.push_back("chunked:alloc=thesis");
  for (const std::string& storage : storages) {
    benchmark::RegisterBenchmark(("generate/" + storage + "/cuda").c_str(), dsm_generate, storage,
                                 Backend::cuda)
        ->Arg(256)
        ->Arg(512)
        ->Arg(1024)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
  for (const std::string& storage : storage_registry().names())
    benchmark::RegisterBenchmark(("render_bilinear/" + storage + "/cuda").c_str(), dsm_render,
                                 storage)
        ->Arg(256)
        ->Arg(1024)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("generate/compact/cpu", dsm_generate, "compact", Backend::cpu)
      ->Arg(256)
      ->Iterations(2)
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond);
}

}  // namespace
}  // namespace dv

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  dv::register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
