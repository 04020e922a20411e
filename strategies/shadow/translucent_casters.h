// The translucent casters of a scene for transmittance shadow mapping: the triangles of every
// object with caster opacity 0 < alpha < 1 and no glass (opaque ones, alpha >= 1, go into a
// depth map, glass, transmission > 0, into its glass layer; alpha 0 surfaces cast nothing), and
// the spread of their opacities, since the method applies one opacity to every set voxel: the
// mean over the objects when they differ.
//
// Methods that store no media see an object's interior medium as its boundary (caster_alphas):
// each crossing of it takes 1 - exp(-sigma d / 2), sigma the medium's extinction (a volume's
// largest) and d the smallest extent of the object's world bounds, so that entering and
// leaving give the medium's transmittance across d; a medium inside glass is a translucent
// caster by that opacity. A BLEND-textured object casts with its factor's alpha (its texels'
// alpha is not voxelized); a MASK-textured one of alpha 1 is opaque where covered and goes into
// the depth map, which cuts it per texel.
#pragma once

#include <vector>

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

// Per object, in scene order: the opacity one crossing of its boundary gets from its interior
// medium (0 without one), as described above.
std::vector<double> medium_crossing_alphas(const SceneData& scene);

// Per object: the caster opacity of one crossing, the larger of its surface's (BLEND textures:
// with the factor's alpha) and its medium's.
std::vector<double> caster_alphas(const SceneData& scene);

}  // namespace dv
