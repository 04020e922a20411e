// The reference renderer of the foundation: per pixel, a ray walks every surface crossing in
// depth order (the BVH gives them one by one), shades translucent surfaces with Phong and
// composites them front to back, integrates constant interiors exactly and samples volumes at
// step midpoints (alpha = 1 - exp(-sigma * length), the last step shortened), with the shadow
// term of each shaded sample from the chosen shadow method. Fragments in front of the near
// plane only toggle inside-ness. Runs on CPU threads or CUDA from the same code.
#pragma once

#include <cstdint>

#include <nlohmann/json.hpp>

#include "core/atomic.h"
#include "core/hd.h"
#include "core/image.h"
#include "cuda/execute.h"
#include "engine/raster/fragment_walk.h"
#include "engine/raster/light_tiles.h"
#include "engine/scene/scene.h"
#include "engine/scene/scene_view.h"
#include "render/frame/oracle_frame.h"
#include "strategies/shadow/shadow_method.h"

namespace dv {

struct RenderCounters {
  unsigned long long hits = 0;             // surface crossings walked
  unsigned long long volume_samples = 0;   // volume samples taken
  unsigned long long max_hits = 0;         // most crossings of one pixel
  unsigned long long overflow_pixels = 0;  // pixels that hit kMaxHitsPerPixel or kMaxInsideObjects
  unsigned long long oracle_flag_pixels = 0;  // pixels whose shadow queries raised oracle flags
  // Filled on the host from the light masks (count_listed_lights), not by count_pixel:
  unsigned long long listed_lights = 0;      // lights each pixel shades with, summed
  unsigned long long max_listed_lights = 0;  // most lights one pixel shades with
};

// Adds one pixel's walk to the counters; any thread of either backend may call it.
DV_HD inline void count_pixel(RenderCounters* c, unsigned long long crossings,
                              unsigned long long samples, bool overflow, uint32_t shadow_flags) {
  // Every pixel adds to the same few counters: combined per warp before the atomics.
  atomic_add_combined(&c->hits, crossings);
  atomic_add_combined(&c->volume_samples, samples);
  atomic_max_combined(&c->max_hits, crossings);
  atomic_add_combined(&c->overflow_pixels, overflow ? 1ull : 0ull);
  atomic_add_combined(&c->oracle_flag_pixels, shadow_flags ? 1ull : 0ull);
}

struct RenderResult {
  Image image;
  RenderCounters counters;
  double milliseconds = 0.0;
  // The exact oracle's deferred pass (render/frame/oracle_frame.h), when it ran: its queries,
  // rounds, buffers and walks.
  OracleFrameStats oracle;
  // The light culling that ran: enabled when the pixels shaded their tiles' culled lists (with
  // culling off they shade lists of every light, not counted here).
  LightCulling light_culling{false, 0.0};
  nlohmann::json stats() const;
};

// `culling`: the lights each pixel evaluates (engine/raster/light_tiles.h).
RenderResult render_reference(Backend backend, const SceneData& scene, const Camera& camera,
                              ShadowMethod& shadows, const dvec3& background,
                              const OracleFrameOptions& oracle = {},
                              const LightCulling& culling = {});

}  // namespace dv
