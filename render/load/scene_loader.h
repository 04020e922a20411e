// Loads whatever a command is given as SCENE: a deepvox JSON scene (schema in
// docs/scene-format.md), a glTF 2.0 file (.gltf/.glb), or a bare mesh file (.obj/.off/.ply/.stl),
// which becomes a scene of that one opaque object with a default camera and light. The result is
// validated.
#pragma once

#include <string>

#include "engine/scene/scene.h"

namespace dv {

// `assets_dir` is where generator assets (the bunny scan) live; empty: found automatically
// (DEEPVOX_ASSETS, then the source tree, then <prefix>/share/deepvox/experiments/assets).
Scene load_scene(const std::string& path, const std::string& assets_dir = "");

// Default assets directory as described above.
std::string find_assets_dir();

}  // namespace dv
