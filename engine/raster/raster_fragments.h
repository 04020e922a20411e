// Crossings of a pixel's ray taken from the rasterizer's tile lists: the triangles whose
// coverage mask holds the pixel centre, each at the exact depth where the pixel ray meets its
// plane, served in (depth, triangle) order. The fragment source of the rasterizing renderer
// (engine/raster/fragment_walk.h). Host and device code.
#pragma once

#include "core/hd.h"
#include "engine/raster/fragment_walk.h"
#include "engine/raster/raster_projection.h"
#include "engine/raster/tile_raster.h"
#include "engine/scene/ray_query.h"
#include "engine/scene/scene_view.h"

namespace dv {

// The nearest crossing after (t_after, after_triangle) among a pixel's fragments. A named
// visitor rather than a lambda: this code is compiled by both g++ and nvcc, and lambda closure
// layouts may differ between the two while their instantiations share one mangled name.
struct NearestFragmentAfter {
  const SceneView* scene;
  const dvec3* origin;
  const dvec3* dir;
  double t_after;
  int64_t after_triangle;
  RayHit* out;
  bool found = false;

  DV_HD void operator()(uint32_t tri) {
    double t;
    bool entering;
    if (!triangle_plane_hit(*scene, tri, *origin, *dir, t, entering)) return;  // seen edge-on
    const bool after = t > t_after || (t == t_after && int64_t(tri) > after_triangle);
    if (after && (!found || t < out->t || (t == out->t && tri < out->triangle))) {
      *out = RayHit{t, tri, entering};
      found = true;
    }
  }
};

struct RasterFragments {
  const SceneView* scene;
  TileListsView lists;
  int x, y;
  dvec3 origin;
  dvec3 dir;

  DV_HD bool next(double t_after, int64_t after_triangle, RayHit& out) const {
    NearestFragmentAfter nearest{scene, &origin, &dir, t_after, after_triangle, &out};
    for_each_fragment(lists, x, y, nearest);
    return nearest.found;
  }
};

// Where a pixel ray of a rasterized view starts being walked: the near plane cuts it at `t` (the
// rasterizer clipped what lies before), and the crossings before that point, found through the
// BVH from the media containing the ray's origin, give the media it is inside there.
struct NearPlaneStart {
  double t;
  WalkStatus status;  // status.inside: the media at t
};

// The ray parameter where the near plane cuts a pixel ray (0 when it starts in front of it).
DV_HD inline double near_plane_ray_t(const RasterProjection& projection, const PixelRay& ray) {
  // The signed distance to the near plane is affine along the ray.
  const double d0 = near_plane_distance(projection, world_to_clip_point(projection, ray.origin));
  const double d1 =
      near_plane_distance(projection, world_to_clip_point(projection, ray.origin + ray.direction));
  return d1 > d0 ? max_value(0.0, -d0 / (d1 - d0)) : 0.0;
}

DV_HD inline NearPlaneStart start_at_near_plane(const SceneView& s,
                                                const RasterProjection& projection,
                                                const PixelRay& ray,
                                                const InsideSet& origin_media) {
  const double t_clip = near_plane_ray_t(projection, ray);
  NoPayload none;
  const BvhFragments before_near{&s, make_sheared_ray(ray.origin, ray.direction), t_clip};
  return {t_clip, walk_fragments(s, before_near, origin_media, 0.0, t_clip, t_clip, none)};
}

}  // namespace dv
