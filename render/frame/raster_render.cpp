// Launch of the rasterizing renderer's passes (see raster_render.h).
#include "render/frame/raster_render.h"

#include <type_traits>
#include <variant>

#include "core/atomic.h"
#include "cuda/buffer.h"
#include "cuda/execute.h"
#include "cuda/pass_timer.h"
#include "render/frame/fragment_lanes.h"
#include "render/frame/fragment_pass.h"
#include "render/frame/oracle_passes.h"
#include "strategies/shadow/shadow_device.h"

namespace dv {

namespace {

// The fragment pass's register budget per shadow source (parallel_for_bounded): two blocks of
// 256 threads per SM (128 registers) make the passes without shadows and with shadow maps about a
// third faster at 4K, but the deep-shadow-map and oracle passes slower (their lookups spill), so
// those keep the occupancy calculator's launch (results/perf/2026-12-06-register-budget).
template <class Source>
inline constexpr int kFragmentMinBlocks = 1;
template <>
inline constexpr int kFragmentMinBlocks<NoShadowSource> = 2;
template <>
inline constexpr int kFragmentMinBlocks<ShadowMapSource> = 2;
// The deferred oracle's walks (render/frame/oracle_passes.h) carry no oracle: the budget
// without shadows.
inline constexpr int kOracleWalkMinBlocks = 2;

SurfaceLooks surface_looks_of(const SceneData& scene) {
  for (const ObjectView& o : scene.host_objects())
    if (!plain_look(o)) return SurfaceLooks::any;
  return SurfaceLooks::plain;
}

}  // namespace

nlohmann::json RasterRenderResult::stats() const {
  nlohmann::json j = render.stats();
  j["renderer"] = "raster";
  j["raster_ms"] = raster_ms;
  j["fragment_ms"] = fragment_ms;
  j["volume_tiles"] = volume_tiles;
  j["plain_looks_pass"] = plain_looks_pass;
  j["raster"] = raster;
  return j;
}

RasterRenderResult render_raster(Backend backend, const SceneData& scene, const Camera& camera,
                                 ShadowMethod& shadows, const dvec3& background,
                                 const OracleFrameOptions& oracle, const LightCulling& culling,
                                 LooksKernel looks_kernel) {
  const Memory memory = memory_of(backend);
  if (scene.memory() != memory) throw Error("render_raster: scene data is in the wrong memory");
  const SceneView& view = scene.view();
  const RasterProjection projection = make_camera_projection(camera, view.bounds);
  RasterRenderResult result;
  const ShadowSourceVariant source = shadows.prepare(scene, backend, &camera);
  PassTimer total(backend);
  PassTimer raster_timer(backend);
  const TileLists lists = rasterize_tiles(backend, view, projection);
  result.raster_ms = raster_timer.stop();
  result.raster = lists.stats;
  if (lists.stats.overflow)
    throw Error("render_raster: tile lists overflowed (" +
                std::to_string(lists.stats.entries_needed) +
                " entries needed); nothing was shaded");
  Buffer<InsideSet> eye_media(memory, 1, "eye media");
  const View<InsideSet> eye = eye_media.view();
  const dvec3 eye_position = camera.position;
  parallel_for(
      backend, "eye_media", 1,
      DV_KERNEL_LAMBDA(int64_t) { eye[0] = media_containing(view, eye_position).inside; });
  Buffer<float> rgb(memory, int64_t(projection.width) * projection.height * 3, "image");
  Buffer<RenderCounters> counters(memory, 1, "render counters");
  counters.fill_zero();
  PassTimer fragment_timer(backend);
  const LightTiles light_tiles = build_light_tiles(backend, view, camera, culling);
  result.render.light_culling = {light_tiles.culled(), culling.cutoff};
  const FragmentOrder tile_order =
      order_fragment_tiles(backend, view, projection, lists.view(), eye_media.data());
  const FragmentPassInputs inputs{
      &view,
      projection,
      lists.view(),
      tile_order.view(),
      background,
      eye_media.data(),
      rgb.view(),
      counters.data(),
      light_tiles.view(),
      looks_kernel == LooksKernel::fitted ? surface_looks_of(scene) : SurfaceLooks::any};
  const int64_t threads = fragment_thread_count(tile_order.order.size());
  std::visit(
      [&](const auto& s) {
        using Source = std::decay_t<decltype(s)>;
        const auto walk_threads = [&](const char* name, int64_t first, int64_t count,
                                      const auto& walk) {
          shade_fragment_threads<kOracleWalkMinBlocks, false>(backend, name, inputs, first, count,
                                                              walk);
        };
        if (run_if_deferred_oracle(backend, s, threads, oracle, result.render.oracle, walk_threads))
          return;
        result.plain_looks_pass = shade_fragment_threads<kFragmentMinBlocks<Source>, true>(
            backend, "raster_fragment_pass", inputs, 0, threads, s);
      },
      source);
  result.fragment_ms = fragment_timer.stop();
  result.render.milliseconds = total.stop();
  result.render.image = Image(projection.width, projection.height);
  result.render.image.rgb = rgb.to_vector();
  if (backend == Backend::cuda) result.device_rgb = std::move(rgb);
  result.render.counters = counters.to_vector()[0];
  const ListedLights listed =
      count_listed_lights(light_tiles, projection.width, projection.height, int(view.lights.size));
  result.render.counters.listed_lights = listed.sum;
  result.render.counters.max_listed_lights = listed.max;
  result.volume_tiles = tile_order.volume_tiles();
  return result;
}

}  // namespace dv
