// Loads whatever a command is given as SCENE: a deepvox JSON scene (schema in
// docs/scene-format.md), a glTF 2.0 file (.gltf/.glb), or a bare mesh file (.obj/.off/.ply/.stl),
// which becomes a scene of that one opaque object with the default camera. A scene without
// lights (a mesh file, a glTF file without lights, a JSON scene importing one) is staged
// (engine/scene/default_staging.h: a ground plane, a key and a fill light from the camera's
// side); `staging` says which scenes get the ground. The result is validated.
#pragma once

#include <string>

#include "engine/scene/default_staging.h"

namespace dv {

// `assets_dir` is where generator assets (the bunny scan) live; empty: found automatically
// (DEEPVOX_ASSETS, then the source tree, then <prefix>/share/deepvox/experiments/assets).
Scene load_scene(const std::string& path, const StagingOptions& staging = {},
                 const std::string& assets_dir = "");

// Default assets directory as described above.
std::string find_assets_dir();

}  // namespace dv
