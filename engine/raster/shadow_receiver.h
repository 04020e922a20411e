// What a shadow lookup is asked about: the receiving point and, for a point on a surface, that
// surface's unit geometric normal. Map methods bias surface points against self-shadowing by
// the receiver's angle to the light (light_faces.h, receiver_depth); points inside media,
// volume samples and free probe points are not surfaces and get no bias. probe_receiver finds
// whether a probe point lies on a surface by the oracle's own convention (a crossing within
// the oracle's end tolerance of the point is AT it). Host and device code.
#pragma once

#include "core/hd.h"
#include "core/math.h"
#include "engine/oracle/transmittance.h"
#include "engine/scene/ray_query.h"
#include "engine/scene/scene_view.h"
#include "engine/scene/surface_transmittance.h"

namespace dv {

struct ShadowReceiver {
  dvec3 point;
  dvec3 normal{0.0};  // unit geometric normal (either orientation); zero: not on a surface

  DV_HD bool on_surface() const { return glm::dot(normal, normal) > 0.0; }
};

// The receiver for a probe point: on the surface (coverage > 0: opaque or glass) that `light`'s
// oracle segment crosses within the oracle's end tolerance of p, if any (the nearest such
// crossing); else a point with no surface.
DV_HD inline ShadowReceiver probe_receiver(const SceneView& s, const LightView& light,
                                           const dvec3& p) {
  ShadowReceiver r{p};
  LightSegment seg;
  if (!make_light_segment(s, light, p, seg) || seg.t_point <= seg.t_light) return r;
  const double eps = kOracleEndTolerance * (s.diagonal + (seg.t_point - seg.t_light));
  const ShearedRay ray = make_sheared_ray(seg.origin, seg.dir);
  double nearest = eps;
  for_each_hit(s, ray, seg.t_point - eps, seg.t_point + eps, [&](const RayHit& h) {
    const double d = h.t > seg.t_point ? h.t - seg.t_point : seg.t_point - h.t;
    const ObjectView& o = s.objects[s.triangle_object[h.triangle]];
    if (hit_coverage(s, o, h.triangle, ray.origin + ray.dir * h.t) > 0.0 && d <= nearest) {
      nearest = d;
      r.normal = triangle_normal(s, h.triangle);
    }
    return true;
  });
  return r;
}

}  // namespace dv
