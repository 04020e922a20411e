// The camera's fragment pass as one launch over a range of its threads (fragment_lanes.h lays
// them out): each thread gathers its pixel's fragments, walks them with the shading payload and
// writes the pixel. Shared by the one-pass frame of every shadow source (raster_render.cpp) and
// the exact oracle's deferred walks (render/frame/walk_hooks.h, oracle_passes.h). Included only
// by nvcc-compiled files (it launches kernels).
#pragma once

#include <cstdint>

#include "cuda/buffer.h"
#include "cuda/execute.h"
#include "engine/raster/fragment_walk.h"
#include "engine/raster/raster_fragments.h"
#include "render/frame/fragment_lanes.h"
#include "render/frame/reference_render.h"
#include "render/frame/shade_payload.h"
#include "render/frame/walk_hooks.h"

namespace dv {

// Everything one launch of the pass needs besides its source.
struct FragmentPassInputs {
  const SceneView* scene;
  RasterProjection projection;
  TileListsView lists;
  FragmentOrderView tile_order;
  dvec3 background;
  const InsideSet* eye_media;
  View<float> rgb;
  RenderCounters* counters;
  LightTilesView lights;  // the lights of each pixel's tile (engine/raster/light_tiles.h)
};

// shade_fragment_threads with (kTiledLights) or without tile light lists.
template <int kMinBlocks, bool kTiledLights, class Source>
void shade_fragment_threads_as(Backend backend, const char* name, const FragmentPassInputs& in,
                               int64_t first, int64_t count, const Source& source) {
  const SceneView& s = *in.scene;
  const RasterProjection projection = in.projection;
  const TileListsView lists = in.lists;
  const FragmentOrderView tile_order = in.tile_order;
  const dvec3 background = in.background;
  const InsideSet* eye_media = in.eye_media;
  const View<float> rgb = in.rgb;
  RenderCounters* counters = in.counters;
  const LightTilesView lights = in.lights;
  const int width = projection.width, height = projection.height;
  parallel_for_bounded<kMinBlocks>(
      backend, name, count, DV_KERNEL_LAMBDA(int64_t i) {
        const int64_t t = first + i;
        int x, y;
        LaneGroup lanes;
        if (!pixel_of_fragment_thread(t, tile_order, width, height, x, y, lanes)) return;
        if (!DV_IN_DEVICE_CODE && lanes.rank > 0) return;  // a CPU thread marches every share
        const int64_t pixel = int64_t(y) * width + x;
        const PixelRay ray = pixel_ray(projection, x, y);
        const NearPlaneStart front = start_at_near_plane(s, projection, ray, *eye_media);
        ShadePayload<Source, kTiledLights> payload{s, source, ray.origin, ray.direction};
        payload.cursor = first_cursor(source, t);
        payload.lanes = lanes;
        const uint32_t* tile_lights = lights.mask_of_pixel(x, y);  // unused without lists
        if constexpr (kTiledLights) payload.light_mask = tile_lights;
        const RasterFragments fragments{&s, lists, x, y, ray.origin, ray.direction};
        const WalkStatus status =
            walk_fragments(s, fragments, front.status.inside, front.t, front.t, 1e300, payload);
        finish_walk(source, payload.cursor, t);
        if (lanes.rank > 0) return;            // the group's lanes ended with the same pixel
        if (!writes_pixels<Source>()) return;  // a walk that only gathers shadow queries
        const dvec3 c = payload.color + payload.transmittance * background;
        rgb[3 * pixel + 0] = float(c.x);
        rgb[3 * pixel + 1] = float(c.y);
        rgb[3 * pixel + 2] = float(c.z);
        count_pixel(counters, status.crossings, payload.samples,
                    status.overflow || front.status.overflow, payload.cursor.flags);
      });
}

// Threads [first, first + count) of the pass; first a multiple of 32, so that lane groups fill
// the same warps as in a launch of all threads. Without tile light lists (one light, or culling
// off) the pass runs a kernel compiled without them, the code it ran before culling existed.
template <int kMinBlocks, class Source>
void shade_fragment_threads(Backend backend, const char* name, const FragmentPassInputs& in,
                            int64_t first, int64_t count, const Source& source) {
  if (in.lights.masks.size == 0)
    shade_fragment_threads_as<kMinBlocks, false>(backend, name, in, first, count, source);
  else
    shade_fragment_threads_as<kMinBlocks, true>(backend, name, in, first, count, source);
}

}  // namespace dv
