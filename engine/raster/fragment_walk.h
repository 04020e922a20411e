// The fragment walk shared by every pass that follows a ray through the scene: the crossings
// of one ray are visited in (depth, triangle) order, the media the ray is inside are tracked
// (closed meshes with an interior: +1 entering, -1 leaving), and a payload receives each
// homogeneous segment between consecutive crossings and each surface crossing. One walk, so
// that the camera, the deep shadow maps and the probes order crossings and track media alike.
// Two plugs:
//   fragments  where the crossings come from: the BVH (BvhFragments, here), a pixel's tile
//              lists of the rasterizer (RasterFragments, raster_fragments.h), or either limited
//              to a face's objects (MaskedFragments, engine/dsm/object_mask.h);
//   payload    what the walk feeds: shading and compositing for the camera
//              (render/frame/shade_payload.h), visibility for deep shadow maps
//              (engine/dsm/visibility_payload.h), nothing but inside-ness (NoPayload, here).
// Host and device code.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "core/math.h"
#include "engine/oracle/transmittance.h"
#include "engine/scene/ray_query.h"
#include "engine/scene/scene_view.h"

namespace dv {

inline constexpr int kMaxInsideObjects = 16;   // media a ray can be inside at once
inline constexpr int kMaxHitsPerPixel = 4096;  // crossings walked per ray before it is flagged

// Media the ray is inside: object ids with their nesting depth.
struct InsideSet {
  int32_t object[kMaxInsideObjects];
  int32_t depth[kMaxInsideObjects];
  int count = 0;
  bool overflow = false;

  DV_HD void cross(int32_t id, bool entering) {
    for (int i = 0; i < count; ++i) {
      if (object[i] != id) continue;
      depth[i] += entering ? 1 : -1;
      if (depth[i] <= 0) object[i] = object[--count], depth[i] = depth[count];
      return;
    }
    if (!entering) return;  // leaving a medium never entered: a crossing behind the walk start
    if (count == kMaxInsideObjects) {
      overflow = true;
      return;
    }
    object[count] = id, depth[count] = 1, ++count;
  }
};

// Crossings of a ray found through the scene's BVH, up to t_max. A fragment source answers
// next(t_after, after_triangle, out): the first crossing after (t_after, after_triangle) in
// (depth, triangle) order, false when there is none.
struct BvhFragments {
  const SceneView* scene;
  ShearedRay ray;
  double t_max = 1e300;
  DV_HD bool next(double t_after, int64_t after_triangle, RayHit& out) const {
    return next_hit(*scene, ray, t_after, after_triangle, t_max, out);
  }
};

struct WalkStatus {
  unsigned long long crossings = 0;
  bool overflow = false;  // kMaxHitsPerPixel or kMaxInsideObjects reached
  InsideSet inside;       // the media the ray is inside where the walk stopped
};

// A payload that only lets the walk track inside-ness.
struct NoPayload {
  DV_HD bool done() const { return false; }
  DV_HD void segment(const InsideSet&, double, double) {}
  DV_HD void surface(const RayHit&, int32_t) {}
};

// Walks the ray from t_start, inside the media `inside` there, to t_far, taking crossings after
// t_start. Segments and surfaces before t_near only update the inside set. Payload interface:
//   bool done() const;                                     stop early (e.g. opacity saturated)
//   void segment(const InsideSet&, double t0, double t1);  only called when inside something
//   void surface(const RayHit&, int32_t object);           a crossing at or beyond t_near
template <class Fragments, class Payload>
DV_HD WalkStatus walk_fragments(const SceneView& s, const Fragments& fragments,
                                const InsideSet& inside_at_start, double t_start, double t_near,
                                double t_far, Payload& payload) {
  WalkStatus status;
  InsideSet& inside = status.inside;
  inside = inside_at_start;
  double t_prev = t_start;
  int64_t tri_prev = -1;
  while (!payload.done()) {
    if (status.crossings == kMaxHitsPerPixel) {
      status.overflow = true;
      break;
    }
    RayHit h;
    const bool found = fragments.next(t_prev, tri_prev, h);
    const double t_end = found ? h.t : t_far;
    const double t_start = max_value(t_prev, t_near);
    if (inside.count > 0 && t_end > t_start) payload.segment(inside, t_start, t_end);
    if (!found) break;
    ++status.crossings;
    const int32_t oi = int32_t(s.triangle_object[h.triangle]);
    if (h.t >= t_near) payload.surface(h, oi);
    if (s.objects[oi].interior != InteriorKind::none) inside.cross(oi, h.entering);
    t_prev = h.t;
    tri_prev = h.triangle;
  }
  status.overflow |= inside.overflow;
  return status;
}

// The media that contain `point`: a walk toward it from outside the scene along a fixed
// direction, counting the crossings strictly before it.
DV_HD inline WalkStatus media_containing(const SceneView& s, const dvec3& point) {
  const dvec3 w = glm::normalize(dvec3(0.267, 0.913, 0.309));
  const Aabb box = padded_bounds(s);
  const double back = max_value(box_exit_distance(box, point, w), 0.0) + 1e-3 * s.diagonal + 1e-6;
  NoPayload none;
  const BvhFragments fragments{&s, make_sheared_ray(point + w * back, -w), back};
  return walk_fragments(s, fragments, InsideSet{}, 0.0, 0.0, back, none);
}

}  // namespace dv
