// `deepvox dsm` (options: its --help, docs/cli.md): generates every light's deep shadow maps
// (always with the compact storage: the strategy does not change the functions) and exports them as
// deep EXR (render/io/deep_exr.h, full build only), as a layers-per-texel heatmap
// (render/io/layer_heatmap.h, every build) and as generation figures with run metadata.
#include <fstream>

#include "apps/deepvox/commands.h"
#include "core/error.h"
#include "core/log.h"
#include "core/text.h"
#include "core/wall_phases.h"
#include "experiments/harness/run_metadata.h"
#include "render/io/dsm_export.h"
#include "render/io/image.h"
#include "render/io/layer_heatmap.h"
#include "render/io/output_path.h"
#include "render/load/scene_loader.h"

namespace dv::cli {

namespace {

struct DsmOptions {
  std::string scene, out, heatmap, stats, backend;
  DsmSettings settings;
};

// Every output path is checked before the (possibly long) generation.
void check_outputs(const DsmOptions& o) {
  if (o.out.empty() && o.heatmap.empty() && o.stats.empty())
    throw InputError("dsm", "nothing to write: give --out, --heatmap or --stats");
  if (!o.out.empty()) {
    if (lowercase_extension(o.out) != ".exr")
      throw InputError(o.out, "deep shadow maps are written as deep OpenEXR: use .exr");
    if (!deep_exr_supported()) write_deep_exr(o.out, DeepMapFile());  // throws the reason
    check_output_path(o.out, {".exr"}, "deep EXR");
  }
  if (!o.heatmap.empty()) check_image_path(o.heatmap);
  if (!o.stats.empty()) check_output_path(o.stats, {".json"}, "stats JSON");
}

nlohmann::json generation_stats(const DsmOptions& o, const DeepShadowMaps& maps, Backend backend) {
  nlohmann::json passes = nlohmann::json::array();
  for (const DsmPass& p : maps.passes())
    passes.push_back({{"name", p.name}, {"ms", p.milliseconds}});
  return {{"meta", run_metadata(backend)},
          {"scene", o.scene},
          {"settings",
           {{"storage", maps.settings().storage},
            {"resolution", maps.resolution()},
            {"eps", maps.settings().eps}}},
          {"lights", maps.layout().lights.size()},
          {"faces", maps.layout().faces.size()},
          {"fragments", maps.fragments()},
          {"generation_ms", maps.generation_milliseconds()},
          {"passes", passes},
          {"figures", maps.figures()},
          {"outputs", {{"exr", o.out}, {"heatmap", o.heatmap}}}};
}

}  // namespace

Runner add_dsm(CLI::App& app) {
  auto opt = std::make_shared<DsmOptions>();
  CLI::App* cmd = app.add_subcommand(
      "dsm", "generate every light's deep shadow maps and export them (deep EXR, heatmap)");
  cmd->add_option("scene", opt->scene, "scene: .json, .gltf/.glb or a mesh file")->required();
  cmd->add_option("--out", opt->out, "deep EXR file, one subimage per map face (full build only)");
  cmd->add_option("--dsm-res", opt->settings.resolution, "texels per side of each map")
      ->capture_default_str();
  cmd->add_option("--eps", opt->settings.eps, "error bound of the visibility functions")
      ->capture_default_str();
  cmd->add_option("--backend", opt->backend, "cpu or cuda (default: cuda when a GPU is present)");
  cmd->add_option("--heatmap", opt->heatmap,
                  "image of layers per texel, labelled faces in a grid, with a colour scale");
  cmd->add_option("--stats", opt->stats, "write generation figures and run metadata as JSON");
  return [opt] {
    check_outputs(*opt);
    // The scene loads while the CUDA driver starts in the background (main.cpp).
    const Scene scene = load_scene(opt->scene);
    if (scene.lights.empty()) throw InputError(opt->scene, "the scene has no lights");
    mark_wall_phase("scene loaded");
    const Backend backend = opt->backend.empty() ? default_backend() : parse_backend(opt->backend);
    require_backend(backend);
    const SceneData data(scene, memory_of(backend));
    mark_wall_phase("scene data built");
    opt->settings.storage = "compact";
    opt->settings.keep_records = !opt->heatmap.empty();  // the heatmap's layers per texel
    DeepShadowMaps maps(opt->settings);
    maps.generate(data, backend);
    mark_wall_phase("maps generated");
    nlohmann::json stats = generation_stats(*opt, maps, backend);
    if (!opt->out.empty())
      write_deep_exr(opt->out, deep_map_file(maps, stats["meta"]["git_sha"].get<std::string>()));
    if (!opt->heatmap.empty())
      write_image(opt->heatmap, layer_heatmap(stored_layers(maps), int(maps.layout().faces.size()),
                                              maps.resolution(), face_labels(maps.layout())));
    mark_wall_phase("maps written");
    stats["wall_ms"] = wall_phases_json();
    if (!opt->stats.empty()) {
      std::ofstream out(opt->stats);
      if (!out) throw InputError(opt->stats, "cannot write stats file");
      out << stats.dump(2) << "\n";
    }
    const nlohmann::json& f = maps.figures();
    log_info("dsm: " + std::to_string(maps.layout().faces.size()) + " faces at " +
             std::to_string(maps.resolution()) + "^2 on " + to_string(backend) + ": " +
             std::to_string(f["nodes"].get<int64_t>()) + " nodes, max " +
             std::to_string(f["max_layers"].get<int64_t>()) + " layers, " +
             std::to_string(maps.generation_milliseconds()) + " ms");
    if (f["walk_overflow_texels"].get<int64_t>() > 0) {
      log_warning(std::to_string(f["walk_overflow_texels"].get<int64_t>()) +
                  " texels overflowed a fixed-size walk structure (their functions are cut)");
      return 3;
    }
    return 0;
  };
}

}  // namespace dv::cli
