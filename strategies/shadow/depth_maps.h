// Depth shadow maps as a building block: the parameters the `shadowmap` method and the
// `transmittance-slicemap` method (its opaque casters) share, the maps of every light face of a
// layout rendered with the tile rasterizer, and the kernel lookup (ShadowMapSource) over them.
// Implemented in shadow_map.cpp, which launches the depth kernel.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/registry.h"
#include "cuda/buffer.h"
#include "cuda/execute.h"
#include "engine/raster/light_faces.h"
#include "strategies/shadow/shadow_map_device.h"

namespace dv {

// res, pcf, bias and slope (depth_map_param_table(): defaults these), the receiver bias of
// surface points (light_faces.h).
struct DepthMapParams {
  int res = 1024;
  int pcf = 2;
  double bias = -1.0;
  double slope = 1.5;

  // Reads the four keys from `p`, resolved against depth_map_param_table().
  static DepthMapParams read(const StrategyParams& p);
  nlohmann::json json() const;
  double bias_for(const SceneView& s) const { return bias >= 0.0 ? bias : 1e-4 * s.diagonal; }
};

// The four parameters of DepthMapParams, as the methods that render depth maps declare them.
const ParamTable& depth_map_param_table();

// A depth map holds one caster per texel, so it decides per fragment whether the surface there
// is opaque: by its caster opacity, the larger of the surface's alpha at that point (a texture's
// coverage there) and, for an object with an interior medium, the opacity of the medium across
// the object (1 - exp(-sigma d), translucent_casters.h), so media boundaries cast.
inline constexpr double kDepthMapOpaqueAlpha = 0.5;

// Which surfaces cast into a depth map.
enum class DepthCasters {
  surfaces,  // caster opacity >= kDepthMapOpaqueAlpha (shadowmap, auto's opaque lights)
  opaque,    // only caster opacity >= 1 (below it: the slicemap's translucent casters)
};
// Glass (transmission > 0) that a depth map leaves out goes into its glass layer.

// The maps of one scene's lights in backend memory.
struct DepthMaps {
  Buffer<float> depths;        // per face res x res nearest caster depths, +inf where none
  Buffer<float> glass_depths;  // the glass layer (shadow_map_device.h); empty without glass
  Buffer<vec3> glass_filters;
  Buffer<ShadowFace> faces;
  Buffer<ShadowLight> lights;
  int res = 0;

  ShadowMapSource source(const SceneView& s, const DepthMapParams& params) const;
  int64_t bytes() const;  // depths and glass layer
};

// Renders every face of `layout` (res x res texels each), or with `rendered` only the faces i
// with rendered[i] != 0, the others left empty (+inf: lit). Throws Error when the rasterizer's
// tile lists overflow.
DepthMaps render_depth_maps(Backend backend, const SceneData& scene, const LightMapLayout& layout,
                            int res, DepthCasters casters,
                            const std::vector<uint8_t>* rendered = nullptr);

}  // namespace dv
