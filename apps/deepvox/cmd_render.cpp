// `deepvox render` (options: its --help, docs/cli.md): the rasterizing renderer (or the BVH
// ray-walk reference) with a shadow method, the camera moved as the viewer moves it (--view), PNG
// (exposed and tone-mapped, ACES by default so a white model under the staged key light keeps its
// shading) or EXR (linear) out, per-frame pass timings and counters in a stats JSON.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

#include "apps/common/error_budget.h"
#include "apps/common/shadow_options.h"
#include "apps/common/staging_options.h"
#include "apps/deepvox/commands.h"
#include "core/log.h"
#include "core/number_text.h"
#include "core/wall_phases.h"
#include "cuda/kernel_timing.h"
#include "cuda/pool_peak.h"
#include "engine/raster/camera_rays.h"
#include "experiments/harness/run_metadata.h"
#include "render/frame/raster_render.h"
#include "render/frame/reference_render.h"
#include "render/io/image.h"
#include "render/io/output_path.h"
#include "render/io/tone_mapping.h"
#include "render/load/gltf_import.h"
#include "render/load/scene_loader.h"

namespace dv::cli {

namespace {

std::string frame_path(const std::string& path, int frame, int frames) {
  if (frames <= 1) return path;
  std::filesystem::path p(path);
  char suffix[16];
  std::snprintf(suffix, sizeof suffix, "_%04d", frame);
  return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).string();
}

// --explain: which lights the pixels evaluated.
void explain_light_culling(const RenderResult& r, int64_t lights, int frame) {
  const double pixels = double(r.image.width) * r.image.height;
  std::cout << "frame " << frame << ": light culling ";
  if (r.light_culling.enabled)
    std::cout << "per " << kLightTilePixels << "x" << kLightTilePixels << "-pixel tile, cut-off "
              << exact_text(r.light_culling.cutoff);
  else
    std::cout << "off (one light and cut-off 0, or --no-light-culling: every pixel evaluates "
                 "every light)";
  std::cout << ": " << fixed_text(pixels > 0 ? double(r.counters.listed_lights) / pixels : 0.0, 2)
            << " of " << lights << " lights per pixel on average, at most "
            << r.counters.max_listed_lights << "\n"
            << std::flush;
}

}  // namespace

Runner add_render(CLI::App& app) {
  struct Options {
    std::string scene, out, stats, backend, renderer = "raster",
                                            tonemap = to_string(kDefaultToneCurve);
    ShadowOptions shadows;
    std::vector<double> view;
    int frames = 1, width = 0, height = 0;
    double orbit = 0.0;
    std::optional<double> exposure;  // unset: the scene's (default_exposure_ev)
    StagingOptions staging;
    LightCulling culling;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd =
      app.add_subcommand("render", "render an image with Phong shading and a shadow method");
  cmd->add_option("scene", opt->scene, "scene: .json, .gltf/.glb or a mesh file")->required();
  cmd->add_option("--out", opt->out, "image file: .png (any build) or .exr (full build)")
      ->required();
  add_shadow_options(cmd, opt->shadows);
  cmd->add_option("--renderer", opt->renderer,
                  "raster: tile rasterizer + fragment walk; raytrace: BVH ray walk (reference)")
      ->check(CLI::IsMember({"raster", "raytrace"}))
      ->capture_default_str();
  cmd->add_option("--backend", opt->backend, "cpu or cuda (default: cuda when a GPU is present)");
  cmd->add_option("--stats", opt->stats, "write timings, counters and run metadata as JSON");
  cmd->add_option("--frames", opt->frames, "number of frames (camera orbits the target)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--orbit", opt->orbit, "total orbit angle in degrees over all frames")
      ->capture_default_str();
  cmd->add_option("--width", opt->width,
                  "image width (default: the scene camera's: a JSON scene's own, 640 for glTF "
                  "and mesh files)")
      ->check(CLI::Range(1, 16384))
      ->default_str("camera");
  cmd->add_option("--height", opt->height,
                  "image height (default: the scene camera's: a JSON scene's own, else 480, or "
                  "640 / aspectRatio for a glTF camera)")
      ->check(CLI::Range(1, 16384))
      ->default_str("camera");
  cmd->add_option("--exposure", opt->exposure,
                  "PNG only: multiply linear values by 2^EV before the tone curve (default: the "
                  "scene's: 0, or log2(683/pi) = 7.76 when every light is a glTF file's "
                  "photometric light)")
      ->check(CLI::Range(-64.0, 64.0))
      ->default_str("scene");
  cmd->add_option("--tonemap", opt->tonemap, "PNG only: tone curve after the exposure")
      ->check(CLI::IsMember({"none", "reinhard", "aces"}))
      ->capture_default_str();
  cmd->add_option("--view", opt->view,
                  "move the scene camera first, as `deepvox view` does: yaw and pitch degrees, "
                  "dolly factor, pan right and up in target distances")
      ->delimiter(',')
      ->expected(5);
  cmd->add_option("--light-cutoff", opt->culling.cutoff,
                  "light culling per 16x16-pixel tile: drop a light where its unshadowed "
                  "irradiance (intensity x brightest colour channel / distance^2) is below this; "
                  "0: drop only lights that add nothing there (outside a spot cone or glTF "
                  "range), which leaves the image unchanged")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_flag(
      "--no-light-culling", [opt](std::int64_t) { opt->culling.enabled = false; },
      "every pixel evaluates every light (every tile lists every light)");
  add_staging_options(cmd, opt->staging);
  return [opt] {
    check_image_path(opt->out);  // before any work: an unwritable output would lose the render
    if (!opt->stats.empty()) check_output_path(opt->stats, {".json"}, "stats JSON");
    auto method = make_shadow_method(opt->shadows);
    // The scene loads first, while the CUDA driver starts in the background (main.cpp): the
    // backend query below waits for the driver.
    Scene scene = load_scene(opt->scene, opt->staging);
    mark_wall_phase("scene loaded");
    const Backend backend = opt->backend.empty() ? default_backend() : parse_backend(opt->backend);
    require_backend(backend);
    const double exposure = opt->exposure.value_or(default_exposure_ev(scene));
    const DisplayTransform display{exposure, parse_tone_curve(opt->tonemap)};
    if (opt->width) scene.camera.width = opt->width;
    if (opt->height) scene.camera.height = opt->height;
    if (!opt->view.empty()) {
      if (!(opt->view[2] > 0.0)) throw InputError("--view", "the dolly factor must be positive");
      scene.camera = moved_camera(
          scene.camera, {opt->view[0], opt->view[1], opt->view[2], opt->view[3], opt->view[4]});
    }
    if (opt->shadows.error_budget) {  // the budget chooses auto's parameters for this scene
      resolve_error_budget(opt->shadows, opt->scene, backend);
      method = make_shadow_method(opt->shadows);
    }
    const SceneData data(scene, memory_of(backend));
    mark_wall_phase("scene data built");
    explain_effects(opt->shadows, scene, *method);
    nlohmann::json stats = {
        // Run metadata (a git call, the device query) only for a stats file that holds it.
        {"meta", opt->stats.empty() ? nlohmann::json::object() : run_metadata(backend)},
        {"scene", opt->scene},
        {"shadows", {{"name", method->name()}, {"params", method->params()}}},
        {"display", {{"exposure_ev", exposure}, {"tonemap", opt->tonemap}}},
        {"triangles", data.triangle_count()},
        {"bvh_depth", data.bvh_depth()},
        {"frames", nlohmann::json::array()}};
    int exit_code = 0;
    for (int f = 0; f < opt->frames; ++f) {
      const Camera cam = orbit_camera(scene.camera, opt->orbit, f, opt->frames);
      nlohmann::json frame;
      RenderResult r;
      if (opt->renderer == "raster") {
        RasterRenderResult rr =
            render_raster(backend, data, cam, *method, scene.background, {}, opt->culling);
        frame = rr.stats();
        r = std::move(rr.render);
      } else {
        r = render_reference(backend, data, cam, *method, scene.background, {}, opt->culling);
        frame = r.stats();
        frame["renderer"] = "raytrace";
      }
      // Per frame only for a stats file, which holds them: a long run without one keeps its
      // memory flat (scripts/soak.sh).
      const bool keep_stats = !opt->stats.empty();
      if (keep_stats) mark_wall_phase("frame " + std::to_string(f) + " rendered");
      const std::string path = frame_path(opt->out, f, opt->frames);
      write_image(path, r.image, display);
      if (keep_stats) mark_wall_phase("frame " + std::to_string(f) + " written");
      frame["image"] = path;
      if (const nlohmann::json plan = method->plan(); !plan.is_null()) frame["plan"] = plan;
      explain_shadows(opt->shadows, *method, "frame " + std::to_string(f));
      if (opt->shadows.explain) explain_light_culling(r, data.view().lights.size, f);
      if (keep_stats) stats["frames"].push_back(frame);
      log_info("render: frame " + std::to_string(f) + " " + std::to_string(r.image.width) + "x" +
               std::to_string(r.image.height) + " " + opt->renderer + " on " + to_string(backend) +
               " with " + method->name() + " shadows: " + std::to_string(r.milliseconds) +
               " ms -> " + path);
      if (r.counters.overflow_pixels || r.counters.oracle_flag_pixels) {
        log_warning("frame " + std::to_string(f) + ": " +
                    std::to_string(r.counters.overflow_pixels) +
                    " pixels overflowed a fixed-size walk structure, " +
                    std::to_string(r.counters.oracle_flag_pixels) + " raised oracle flags");
        exit_code = 3;
      }
      if (keep_stats) {  // rewrite after every frame: nothing computed is lost
        stats["shadows"]["stats"] = method->stats();
        if (kernel_timing_enabled()) stats["kernels"] = kernel_timings_json();
        if (backend == Backend::cuda) stats["device_memory"] = device_pool_peak().stats();
        stats["wall_ms"] = wall_phases_json();
        std::ofstream out(opt->stats);
        if (!out) throw InputError(opt->stats, "cannot write stats file");
        out << stats.dump(2) << "\n";
      }
    }
    return exit_code;
  };
}

}  // namespace dv::cli
