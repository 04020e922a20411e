// The translucent casters of a scene for transmittance shadow mapping: the triangles of every
// object with surface opacity 0 < alpha < 1 and no glass (opaque ones, alpha >= 1, go into a
// depth map, glass, transmission > 0, into its glass layer; alpha 0 surfaces cast nothing), and the
// spread of their opacities, since the method applies one opacity to every set voxel: the mean over
// the objects when they differ.
#pragma once

#include <nlohmann/json.hpp>

#include "engine/scene/scene_view.h"
#include "strategies/voxelizer/triangle_soup.h"

namespace dv {

struct TranslucentCasters {
  TriangleSoup soup;  // world space
  int objects = 0;    // translucent objects owning at least one triangle
  double alpha_min = 0.0, alpha_max = 0.0, alpha_mean = 0.0;  // over those objects; 0 if none

  // {"objects", "alpha_min", "alpha_max", "alpha_mean", "alphas_differ"}.
  nlohmann::json json() const;
};

// Reads the scene's triangles back to the host when it lives in device memory.
TranslucentCasters gather_translucent_casters(const SceneData& scene);

}  // namespace dv
