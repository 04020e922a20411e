// `deepvox view` (options: its --help, docs/cli.md; shared with render where they mean the same):
// the interactive viewer (apps/viewer), built into the full binary where GLFW and OpenGL are.
#include "apps/common/error_budget.h"
#include "apps/common/shadow_options.h"
#include "apps/common/staging_options.h"
#include "apps/deepvox/commands.h"
#include "apps/viewer/viewer.h"
#include "apps/viewer/viewer_keys.h"
#include "core/error.h"

namespace dv::cli {

Runner add_view(CLI::App& app) {
  auto run = std::make_shared<viewer::ViewerRun>();
  auto view = std::make_shared<std::vector<double>>();
  viewer::ViewerSetup& s = run->setup;
  CLI::App* cmd = app.add_subcommand(
      "view", "interactive viewer (GLFW, OpenGL 4.5): camera, shadow method, overlays; keys:\n" +
                  viewer::keys_help());
  cmd->add_option("scene", s.scene_path, "scene: .json, .gltf/.glb or a mesh file")->required();
  add_shadow_options(cmd, s.shadows);
  cmd->add_option("--backend", s.backend, "cpu or cuda (default: cuda when a GPU is present)");
  cmd->add_option("--width", s.width, "override the camera's image width")
      ->check(CLI::Range(1, 16384));
  cmd->add_option("--height", s.height, "override the camera's image height")
      ->check(CLI::Range(1, 16384));
  cmd->add_option("--exposure", s.exposure,
                  "multiply linear values by 2^EV (as render's PNG; default: the scene's)")
      ->check(CLI::Range(-64.0, 64.0))
      ->default_str("scene");
  cmd->add_option("--tonemap", s.tonemap, "tone curve after the exposure (as render's PNG)")
      ->check(CLI::IsMember({"none", "reinhard", "aces"}))
      ->capture_default_str();
  add_staging_options(cmd, s.staging);
  cmd->add_option("--view", *view, "start camera move: yaw, pitch, dolly, pan x, pan y")
      ->delimiter(',')
      ->expected(5);
  cmd->add_option("--frames", run->frames, "exit after N frames (headless use)")
      ->check(CLI::Range(1, 100000000));
  cmd->add_option("--screenshot", run->screenshot,
                  "after the last frame: the rendered image, as `render --out` writes it");
  cmd->add_option("--screenshot-window", run->screenshot_window,
                  "after the last frame: the window's framebuffer with overlays (PNG)");
  cmd->add_option("--script", run->script, "key presses and mouse moves by frame (docs/viewer.md)");
  cmd->add_option("--save-prefix", run->save_prefix,
                  "S writes PREFIX_NNN.png, .json (stats) and .txt (render command line)")
      ->capture_default_str();
  return [run, view] {
    if (!view->empty()) {
      const std::vector<double>& v = *view;
      if (!(v[2] > 0.0)) throw InputError("--view", "the dolly factor must be positive");
      run->setup.start = {v[0], v[1], v[2], v[3], v[4]};
    }
    viewer::ViewerSetup& setup = run->setup;
    resolve_error_budget(setup.shadows, setup.scene_path,
                         setup.backend.empty() ? default_backend() : parse_backend(setup.backend));
    return viewer::run_viewer(*run);
  };
}

}  // namespace dv::cli
