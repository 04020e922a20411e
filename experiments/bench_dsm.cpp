// Deep-shadow-map generation and filtered rendering per storage strategy on
// scenes/knecht-fig56.json (one spot light, two 128^3 volumes, eight polyhedra, 720x480) at DSM
// 256^2, 512^2 and 1024^2, eps 0.05, on the GPU with CUDA events: generation is every pass
// (light-view rasterization, counting, scan, writes, re-layout), rendering is the camera
// pass with bilinear DSM lookups (maps generated once before). Counters carry the memory
// figures beside Knecht 2011 §5.8's formulas: texture3d d^2 * layers * 64 bit, chunked
// d^2 * layers (variable) * 128 bit + d^2 * 64 bit. Knecht (GTX 480) took 7-65 ms to generate and
// 46-57 ms to render.
// lights32/*: scenes/knecht-32-lights.json (many lights, optionally clustered; see many_lights).
// Run: build/bin/bench_dsm --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "cuda/device_memory.h"
#include "dsm/deep_shadow_maps.h"
#include "frame/raster_render.h"
#include "load/scene_loader.h"
#include "strategies/shadow/shadow_method.h"
#include "tests/support/paths.h"

namespace dv {
namespace {

constexpr const char* kScene = "knecht-fig56.json";

const Scene& bench_scene() {
  static const Scene scene = load_scene(test::source_dir() + "/scenes/" + kScene);
  return scene;
}

DsmSettings settings(const std::string& storage, int res, bool bilinear) {
  DsmSettings s;
  const size_t colon = storage.find(':');
  s.storage = storage.substr(0, colon);
  if (colon != std::string::npos)
    s.storage_params = StrategyParams::parse({storage.substr(colon + 1)});
  s.resolution = res;
  s.eps = 0.05f;
  s.bilinear = bilinear;
  return s;
}

void report_figures(benchmark::State& state, const DeepShadowMaps& maps) {
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
}

void dsm_generate(benchmark::State& state, std::string storage, Backend backend) {
  std::string why;
  if (backend == Backend::cuda && !cuda_device_available(&why))
    return state.SkipWithError(why.c_str());
  const SceneData data(bench_scene(), memory_of(backend));
  DeepShadowMaps maps(settings(storage, int(state.range(0)), false));
  maps.generate(data, backend);  // warm-up: allocations, first-touch
  for (auto _ : state) {
    maps.generate(data, backend);
    state.SetIterationTime(maps.generation_milliseconds() / 1e3);
  }
  report_figures(state, maps);
  state.SetLabel(backend == Backend::cuda ? cuda_device_name() : "cpu");
}

void dsm_render(benchmark::State& state, std::string storage) {
  std::string why;
  if (!cuda_device_available(&why)) return state.SkipWithError(why.c_str());
  const Scene& scene = bench_scene();
  const SceneData data(scene, Memory::device);
  auto method = shadow_registry().create(
      "dsm", StrategyParams::parse({"storage=" + storage, "res=" + std::to_string(state.range(0)),
                                    "eps=0.05", "filter=bilinear"}));
  render_raster(Backend::cuda, data, scene.camera, *method, scene.background);  // generates
  double fragment_ms = 0.0;
  for (auto _ : state) {
    const RasterRenderResult r =
        render_raster(Backend::cuda, data, scene.camera, *method, scene.background);
    state.SetIterationTime((r.raster_ms + r.fragment_ms) / 1e3);
    fragment_ms += r.fragment_ms;
  }
  state.counters["fragment_ms"] = fragment_ms / double(state.iterations());
  state.counters["maps_built"] = method->stats()["maps_built"].get<double>();
  state.SetLabel(cuda_device_name());
}

// scenes/knecht-32-lights.json (the same objects under 16 spot and 16 omni lights): maps of
// every light generated, then one rasterized frame with bilinear lookups of all 32 lights;
// range(0) = res, range(1) = clusters. On the CPU at a small image and resolution so it runs
// anywhere; on CUDA at the scene's image size.
void many_lights(benchmark::State& state, Backend backend) {
  std::string why;
  if (backend == Backend::cuda && !cuda_device_available(&why))
    return state.SkipWithError(why.c_str());
  static const Scene many = load_scene(test::source_dir() + "/scenes/knecht-32-lights.json");
  Scene scene = many;
  if (backend == Backend::cpu) scene.camera.width = 120, scene.camera.height = 80;
  const SceneData data(scene, memory_of(backend));
  double generation_ms = 0.0, fragment_ms = 0.0;
  for (auto _ : state) {
    auto method = shadow_registry().create(
        "dsm", StrategyParams::parse({"res=" + std::to_string(state.range(0)),
                                      "clusters=" + std::to_string(state.range(1)), "eps=0.05",
                                      "filter=bilinear"}));
    const RasterRenderResult r =
        render_raster(backend, data, scene.camera, *method, scene.background);
    const nlohmann::json stats = method->stats();
    generation_ms += stats["generation_ms"].get<double>();
    fragment_ms += r.fragment_ms;
    state.SetIterationTime((stats["generation_ms"].get<double>() + r.raster_ms + r.fragment_ms) /
                           1e3);
    state.counters["maps"] = stats["faces"].get<double>();
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
  for (const char* storage :
       {"compact", "texture3d", "chunked", "chunked:alloc=thesis", "blocked"}) {
    benchmark::RegisterBenchmark((std::string("generate/") + storage + "/cuda").c_str(),
                                 dsm_generate, storage, Backend::cuda)
        ->Arg(256)
        ->Arg(512)
        ->Arg(1024)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
  for (const char* storage : {"compact", "texture3d", "chunked", "blocked"})
    benchmark::RegisterBenchmark((std::string("render_bilinear/") + storage + "/cuda").c_str(),
                                 dsm_render, storage)
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
