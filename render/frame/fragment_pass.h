// The camera's fragment pass as one launch over a range of its threads (fragment_lanes.h lays
// them out): each thread gathers its pixel's fragments, walks them with the shading payload and
// writes the pixel. Shared by the one-pass frame of every shadow source (raster_render.cpp) and
// the exact oracle's deferred walks (render/frame/walk_hooks.h, oracle_passes.h). Included only
// by nvcc-compiled files (it launches kernels).
#pragma once

#include <cstdint>

#include "cuda/buffer.h"
#include "cuda/execute.h"
#include "cuda/execute_with_tables.h"
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
  SurfaceLooks looks;     // plain: every object of the scene has a plain look (shade_payload.h)
};

// What one thread of the pass does: gather its pixel's fragments, walk them shading with
// `source` and the scene's lights `lights` (where they are or a block's copy), write the pixel.
template <class Source, bool kTiledLights, SurfaceLooks kLooks>
struct FragmentThread {
  SceneView s;  // a copy of *in.scene: in.scene points into host memory
  FragmentPassInputs in;
  int64_t first;

  DV_HD void operator()(int64_t i, const Source& source, View<const LightView> lights) const {
    const int64_t t = first + i;
    const int width = in.projection.width, height = in.projection.height;
    int x, y;
    LaneGroup lanes;
    if (!pixel_of_fragment_thread(t, in.tile_order, width, height, x, y, lanes)) return;
    if (!DV_IN_DEVICE_CODE && lanes.rank > 0) return;  // a CPU thread marches every share
    const int64_t pixel = int64_t(y) * width + x;
    const PixelRay ray = pixel_ray(in.projection, x, y);
    const NearPlaneStart front = start_at_near_plane(s, in.projection, ray, *in.eye_media);
    ShadePayload<Source, kTiledLights, kLooks> payload{s, source, ray.origin, ray.direction};
    if constexpr (kTiledLights) payload.lights.table = lights;
    payload.cursor = first_cursor(source, t);
    payload.lanes = lanes;
    const uint32_t* tile_lights = in.lights.mask_of_pixel(x, y);  // unused without lists
    if constexpr (kTiledLights) payload.light_mask = tile_lights;
    const RasterFragments fragments{&s, in.lists, x, y, ray.origin, ray.direction};
    const WalkStatus status =
        walk_fragments(s, fragments, front.status.inside, front.t, front.t, 1e300, payload);
    finish_walk(source, payload.cursor, t);
    if (lanes.rank > 0) return;            // the group's lanes ended with the same pixel
    if (!writes_pixels<Source>()) return;  // a walk that only gathers shadow queries
    const dvec3 c = payload.color + payload.transmittance * in.background;
    in.rgb[3 * pixel + 0] = float(c.x);
    in.rgb[3 * pixel + 1] = float(c.y);
    in.rgb[3 * pixel + 2] = float(c.z);
    count_pixel(in.counters, status.crossings, payload.samples,
                status.overflow || front.status.overflow, payload.cursor.flags);
  }
};

// Shadow sources with per-light and per-face headers (shadow maps, deep shadow maps).
template <class Source>
concept HasFaceHeaders = requires(Source& source) {
  source.lights;
  source.light_faces;
  source.faces;
};

// Where a source's headers lie in a block's copy of a launch's shared tables (-1: not there).
struct FaceHeaderOffsets {
  int32_t lights = -1;
  int32_t light_faces = -1;
  int32_t faces = -1;

  // The source reading its headers from the block's copy `copy` where they were placed (a
  // copy of it); a source without such headers itself.
  template <class Source>
  DV_HD decltype(auto) reading(const unsigned char* copy, const Source& source) const {
    if constexpr (HasFaceHeaders<Source>) {
      Source placed = source;
      placed.lights = placed_view(source.lights, lights, copy);
      placed.light_faces = placed_view(source.light_faces, light_faces, copy);
      placed.faces = placed_view(source.faces, faces, copy);
      return placed;
    } else {
      return (source);
    }
  }
};

// shade_fragment_threads with (kTiledLights) or without tile light lists, for surfaces of looks
// kLooks. With lists (several lights) a block first copies the lights and the source's light and
// face headers into its shared memory, in that order as far as they fit (cuda/shared_tables.h):
// every pixel reads them once per listed light.
template <int kMinBlocks, bool kTiledLights, SurfaceLooks kLooks, class Source>
void shade_fragment_threads_as(Backend backend, const char* name, const FragmentPassInputs& in,
                               int64_t first, int64_t count, const Source& source) {
  const FragmentThread<Source, kTiledLights, kLooks> thread{*in.scene, in, first};
  if constexpr (!kTiledLights) {
    parallel_for_bounded<kMinBlocks>(
        backend, name, count, DV_KERNEL_LAMBDA(int64_t i) { thread(i, source, thread.s.lights); });
  } else {
    SharedTables tables;
    const int scene_lights = tables.add(in.scene->lights);
    int headers[3] = {-1, -1, -1};
    if constexpr (HasFaceHeaders<Source>) {
      headers[0] = tables.add(source.lights);
      headers[1] = tables.add(source.light_faces);
      headers[2] = tables.add(source.faces);
    }
    tables.place(shared_table_budget<kMinBlocks>(backend));
    const int32_t lights_at = tables.placed_offset(scene_lights);
    const FaceHeaderOffsets at{tables.placed_offset(headers[0]), tables.placed_offset(headers[1]),
                               tables.placed_offset(headers[2])};
    parallel_for_with_tables<kMinBlocks>(
        backend, name, count, tables, DV_KERNEL_LAMBDA(int64_t i, const unsigned char* copy) {
          thread(i, at.reading(copy, source), placed_view(thread.s.lights, lights_at, copy));
        });
  }
}

// Threads [first, first + count) of the pass; first a multiple of 32, so that lane groups fill
// the same warps as in a launch of all threads. Without tile light lists (one light, or culling
// off) the pass runs a kernel compiled without them, the code it ran before culling existed; and
// with kPlainLooksKernel, on a scene whose surfaces are all plain (in.looks), one compiled for
// plain looks only (then it returns true). Passes with lists and the oracle's walks keep the
// general payload.
template <int kMinBlocks, bool kPlainLooksKernel, class Source>
bool shade_fragment_threads(Backend backend, const char* name, const FragmentPassInputs& in,
                            int64_t first, int64_t count, const Source& source) {
  constexpr SurfaceLooks any = SurfaceLooks::any;
  if (in.lights.masks.size != 0) {
    shade_fragment_threads_as<kMinBlocks, true, any>(backend, name, in, first, count, source);
    return false;
  }
  if constexpr (kPlainLooksKernel) {
    if (in.looks == SurfaceLooks::plain) {
      shade_fragment_threads_as<kMinBlocks, false, SurfaceLooks::plain>(backend, name, in, first,
                                                                        count, source);
      return true;
    }
  }
  shade_fragment_threads_as<kMinBlocks, false, any>(backend, name, in, first, count, source);
  return false;
}

}  // namespace dv
