// Launch of the reference renderer's pixel walk on the chosen backend (see reference_render.h).
#include "render/frame/reference_render.h"

#include <chrono>
#include <variant>

#include "cuda/buffer.h"
#include "render/frame/oracle_passes.h"
#include "render/frame/ray_walk.h"

namespace dv {

namespace {

// Pixels [first, first + count) in row order.
template <class Source>
void render_pixels(Backend backend, const char* name, const SceneView& view, const CameraView& cam,
                   const LightTilesView& lights, int64_t first, int64_t count, const Source& source,
                   const dvec3& background, View<float> rgb, RenderCounters* counters) {
  parallel_for(
      backend, name, count, DV_KERNEL_LAMBDA(int64_t k) {
        const int64_t i = first + k;
        const int x = int(i % cam.width), y = int(i / cam.width);
        const dvec3 c =
            walk_pixel(view, cam, source, x, y, lights.mask_of_pixel(x, y), background, counters);
        if (!writes_pixels<Source>()) return;  // a walk that only gathers shadow queries
        rgb[3 * i + 0] = float(c.x);
        rgb[3 * i + 1] = float(c.y);
        rgb[3 * i + 2] = float(c.z);
      });
}

}  // namespace

nlohmann::json RenderResult::stats() const {
  const double pixels = double(image.width) * image.height;
  nlohmann::json j = {
      {"milliseconds", milliseconds},
      {"width", image.width},
      {"height", image.height},
      {"hits", counters.hits},
      {"hits_per_pixel_mean", pixels > 0 ? double(counters.hits) / pixels : 0.0},
      {"hits_per_pixel_max", counters.max_hits},
      {"volume_samples", counters.volume_samples},
      {"overflow_pixels", counters.overflow_pixels},
      {"oracle_flag_pixels", counters.oracle_flag_pixels},
      {"lights_per_pixel_mean", pixels > 0 ? double(counters.listed_lights) / pixels : 0.0},
      {"lights_per_pixel_max", counters.max_listed_lights},
      {"light_culling",
       {{"tiled", light_culling.enabled},
        {"tile_pixels", kLightTilePixels},
        {"cutoff", light_culling.cutoff}}}};
  if (oracle.deferred()) j["oracle_pass"] = oracle.stats();
  return j;
}

RenderResult render_reference(Backend backend, const SceneData& scene, const Camera& camera,
                              ShadowMethod& shadows, const dvec3& background,
                              const OracleFrameOptions& oracle, const LightCulling& culling) {
  const Memory memory = memory_of(backend);
  if (scene.memory() != memory) throw Error("render_reference: scene data is in the wrong memory");
  const CameraView cam = make_camera_view(camera);
  Buffer<float> rgb(memory, int64_t(cam.width) * cam.height * 3, "image");
  Buffer<RenderCounters> counters(memory, 1, "render counters");
  counters.fill_zero();
  const ShadowSourceVariant source = shadows.prepare(scene, backend, &camera);
  const auto start = std::chrono::steady_clock::now();
  const SceneView& view = scene.view();
  const LightTiles light_tiles = build_light_tiles(backend, view, camera, culling);
  const LightTilesView lights = light_tiles.view();
  const int64_t pixels = int64_t(cam.width) * cam.height;
  RenderResult result;
  result.light_culling = {light_tiles.culled(), culling.cutoff};
  std::visit(
      [&](const auto& s) {
        const auto walk_pixels = [&](const char* name, int64_t first, int64_t count,
                                     const auto& walk) {
          render_pixels(backend, name, view, cam, lights, first, count, walk, background,
                        rgb.view(), counters.data());
        };
        if (run_if_deferred_oracle(backend, s, pixels, oracle, result.oracle, walk_pixels)) return;
        render_pixels(backend, "render_reference", view, cam, lights, 0, pixels, s, background,
                      rgb.view(), counters.data());
      },
      source);
  if (backend == Backend::cuda) device_synchronize("render_reference");
  result.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  result.image = Image(cam.width, cam.height);
  result.image.rgb = rgb.to_vector();
  result.counters = counters.to_vector()[0];
  const ListedLights listed =
      count_listed_lights(light_tiles, cam.width, cam.height, int(view.lights.size));
  result.counters.listed_lights = listed.sum;
  result.counters.max_listed_lights = listed.max;
  return result;
}

}  // namespace dv
