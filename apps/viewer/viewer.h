// `deepvox view`: the interactive viewer (GLFW window, OpenGL 4.5 core). Shows the renderer's
// image of a ViewerState, turns window input into the script's events, replays a script, and
// writes screenshots. Usage and keys: docs/viewer.md.
#pragma once

#include <string>

#include "apps/viewer/viewer_state.h"

namespace dv::viewer {

struct ViewerRun {
  ViewerSetup setup;
  std::string script;             // events to replay (viewer_script.h)
  int frames = 0;                 // > 0: exit after this many frames (else on close / script end)
  std::string screenshot;         // after the last frame: the rendered image, as `render` writes it
  std::string screenshot_window;  // after the last frame: the window's framebuffer, overlays too
  std::string save_prefix = "deepvox-view";  // S writes PREFIX_NNN.png/.json/.txt
};

// Exit code: 0, or throws InputError (bad script, scene, method) / Error (no display, GL).
int run_viewer(const ViewerRun& run);

}  // namespace dv::viewer
