// Restricting a deep shadow map face to a subset of the scene's objects (clustered deep shadow
// maps, Knecht 2011 §3.4.3: "only the objects within the cluster are rasterized"): a bit mask of
// object ids per face, a fragment source that skips the crossings of other objects, the media
// set without them, and the near-plane start of a pixel ray that only sees them. A face without
// a mask sees every object. Host and device code.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "cuda/buffer.h"
#include "engine/raster/fragment_walk.h"
#include "engine/raster/raster_fragments.h"
#include "engine/scene/scene_view.h"

namespace dv {

// Objects one face sees: bit (object % 32) of words[first_word + object / 32]; every object when
// first_word < 0.
struct ObjectMask {
  View<const uint32_t> words;
  int64_t first_word = -1;

  DV_HD bool contains(int32_t object) const {
    if (first_word < 0) return true;
    return ((words[first_word + object / 32] >> (object % 32)) & 1u) != 0u;
  }
};

// Another fragment source's crossings of the masked objects only.
template <class Inner>
struct MaskedFragments {
  const SceneView* scene;
  Inner inner;
  ObjectMask mask;

  DV_HD bool next(double t_after, int64_t after_triangle, RayHit& out) const {
    while (inner.next(t_after, after_triangle, out)) {
      if (mask.contains(int32_t(scene->triangle_object[out.triangle]))) return true;
      t_after = out.t;
      after_triangle = out.triangle;
    }
    return false;
  }
};

// The media of `inside` that the mask holds.
DV_HD inline InsideSet masked_media(const InsideSet& inside, const ObjectMask& mask) {
  InsideSet kept;
  kept.overflow = inside.overflow;
  for (int i = 0; i < inside.count; ++i) {
    if (!mask.contains(inside.object[i])) continue;
    kept.object[kept.count] = inside.object[i];
    kept.depth[kept.count] = inside.depth[i];
    ++kept.count;
  }
  return kept;
}

// start_at_near_plane (engine/raster/raster_fragments.h) seeing only the masked objects.
DV_HD inline NearPlaneStart masked_start_at_near_plane(const SceneView& s,
                                                       const RasterProjection& projection,
                                                       const PixelRay& ray,
                                                       const InsideSet& origin_media,
                                                       const ObjectMask& mask) {
  const double t_clip = near_plane_ray_t(projection, ray);
  NoPayload none;
  const MaskedFragments<BvhFragments> before_near{
      &s, BvhFragments{&s, make_sheared_ray(ray.origin, ray.direction), t_clip}, mask};
  return {t_clip, walk_fragments(s, before_near, masked_media(origin_media, mask), 0.0, t_clip,
                                 t_clip, none)};
}

}  // namespace dv
