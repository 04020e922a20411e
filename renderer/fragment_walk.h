// The fragment walk shared by every renderer pass: the crossings of one ray are visited in
// (depth, triangle) order, the media the ray is inside are tracked (closed meshes with an
// interior: +1 entering, -1 leaving), and a payload receives each homogeneous segment between
// consecutive crossings and each surface crossing. The camera pass plugs in shading and
// compositing (renderer/shade_payload.h); the deep-shadow-map pass will plug in a visibility
// payload. Where the crossings come from is a second plug: the BVH (ray walk) here, per-pixel
// tile lists of the rasterizer later. Host and device code.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "core/math.h"
#include "scene/ray_query.h"
#include "scene/scene_view.h"

namespace dv {

inline constexpr int kMaxInsideObjects = 16;  // media a ray can be inside at once
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

// Crossings of a ray found through the scene's BVH.
struct BvhFragments {
  const SceneView* scene;
  ShearedRay ray;
  DV_HD bool next(double t_after, int64_t after_triangle, RayHit& out) const {
    return next_hit(*scene, ray, t_after, after_triangle, 1e300, out);
  }
};

struct WalkStatus {
  unsigned long long crossings = 0;
  bool overflow = false;  // kMaxHitsPerPixel or kMaxInsideObjects reached
};

// Walks the ray origin + t * dir from t = 0 (a point outside every medium) to t_far. Segments
// and surfaces before t_near only update the inside set. Payload interface:
//   bool done() const;                                     stop early (e.g. opacity saturated)
//   void segment(const InsideSet&, double t0, double t1);  only called when inside something
//   void surface(const RayHit&, int32_t object);           a crossing at or beyond t_near
template <class Fragments, class Payload>
DV_HD WalkStatus walk_fragments(const SceneView& s, const Fragments& fragments, double t_near, double t_far,
                                Payload& payload) {
  InsideSet inside;
  WalkStatus status;
  double t_prev = 0.0;
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

}  // namespace dv
