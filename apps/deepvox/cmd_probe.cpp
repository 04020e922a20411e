// `deepvox probe` (options: its --help, docs/cli.md; the shadow options are those of render,
// apps/common/shadow_options.h): the transmittance of every light at every point. Points whose
// answer raised an oracle flag are still written (nothing computed is lost), reported, and make the
// exit code 3.
#include <cstdio>

#include "apps/common/error_budget.h"
#include "apps/common/shadow_options.h"
#include "apps/deepvox/commands.h"
#include "core/log.h"
#include "cuda/device_memory.h"
#include "cuda/execute.h"
#include "engine/scene/scene_view.h"
#include "render/io/output_path.h"
#include "render/io/points_csv.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/probe.h"

namespace dv::cli {

Runner add_probe(CLI::App& app) {
  struct Options {
    std::string scene, points, out, backend;
    ShadowOptions shadows;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd =
      app.add_subcommand("probe", "transmittance of each light at given points (CSV in, CSV out)");
  cmd->add_option("scene", opt->scene, "scene: .json, .gltf/.glb or a mesh file")->required();
  cmd->add_option("--points", opt->points, "CSV of points, x,y,z per line (header optional)")
      ->required();
  cmd->add_option(
         "--out", opt->out,
         "output CSV: x,y,z,light0,light1,... (luminance), then light0_r,light0_g,light0_b,...")
      ->required();
  add_shadow_options(cmd, opt->shadows);
  cmd->add_option("--backend", opt->backend, "cpu or cuda (default: cuda when a GPU is present)");
  return [opt] {
    check_output_path(opt->out, {".csv"}, "transmittance CSV");  // before any work
    const Backend backend = opt->backend.empty() ? default_backend() : parse_backend(opt->backend);
    require_backend(backend);
    auto method = make_shadow_method(opt->shadows);
    const Scene scene = load_scene(opt->scene);
    if (opt->shadows.error_budget) {  // the budget chooses auto's parameters for this scene
      resolve_error_budget(opt->shadows, opt->scene, backend);
      method = make_shadow_method(opt->shadows);
    }
    const std::vector<dvec3> points = read_points_csv(opt->points);
    const SceneData data(scene, memory_of(backend));
    const ProbeResults r = probe_transmittance(backend, data, *method, points);
    write_transmittance_csv(opt->out, points, r.transmittance, r.rgb, r.light_count);
    explain_effects(opt->shadows, scene, *method);
    explain_shadows(opt->shadows, *method, "probe");
    int flagged = 0;
    for (uint32_t f : r.flags) flagged += f != 0;
    log_info("probe: " + std::to_string(points.size()) + " points x " +
             std::to_string(r.light_count) + " lights, " + method->name() + " on " +
             to_string(backend) + ", " + std::to_string(r.milliseconds) + " ms -> " + opt->out);
    if (flagged) {
      log_warning(std::to_string(flagged) +
                  " answers raised flags (oracle: more volume crossings on a ray than it "
                  "holds); they are written but not exact");
      return 3;
    }
    return 0;
  };
}

}  // namespace dv::cli
