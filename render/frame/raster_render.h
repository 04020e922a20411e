// The rasterizing renderer (Knecht 2011 §3.1, §4.1; Bornik 2012 §3): the scene is binned into
// 8x8-tile lists by the tile rasterizer, then every pixel gathers its fragments from its tile,
// sorts them by exact depth and walks them with the shading payload. The walk starts inside
// the media that contain the eye; crossings between the eye and the near plane (clipped away
// by the rasterizer) come from the BVH, so they toggle inside-ness but are never shaded.
// CPU threads or CUDA from the same code; per-pass times and counters in RasterRenderResult.
#pragma once

#include <nlohmann/json.hpp>

#include "cuda/buffer.h"
#include "cuda/execute.h"
#include "engine/raster/tile_raster.h"
#include "render/frame/reference_render.h"

namespace dv {

struct RasterRenderResult {
  RenderResult render;       // image, walk counters, total milliseconds
  RasterStats raster;        // triangles, clipping, tile entries, overflow
  double raster_ms = 0.0;    // binning into tile lists
  double fragment_ms = 0.0;  // tile order, per-pixel gather, sort, walk and shading
  int64_t volume_tiles = 0;  // tiles whose pixels split their volume steps between lanes
  // Whether the camera pass ran its kernel for plain surface looks (every object untextured,
  // without glass and not emitting: render/frame/shade_payload.h); oracle frames and passes with
  // light lists never do.
  bool plain_looks_pass = false;
  // CUDA: the image still in device memory (linear rgb, as render.image.rgb), for display
  // without a host round trip (the viewer's CUDA-GL interop); empty on the CPU.
  Buffer<float> device_rgb;
  nlohmann::json stats() const;
};

// Which camera-pass kernel a scene whose surfaces are all plain runs: the one compiled for plain
// looks (fitted), or the general one every other scene runs (general: for A/B and tests).
enum class LooksKernel { fitted, general };

// `culling`: the lights each pixel evaluates (engine/raster/light_tiles.h).
RasterRenderResult render_raster(Backend backend, const SceneData& scene, const Camera& camera,
                                 ShadowMethod& shadows, const dvec3& background,
                                 const OracleFrameOptions& oracle = {},
                                 const LightCulling& culling = {},
                                 LooksKernel looks_kernel = LooksKernel::fitted);

}  // namespace dv
