// The exact transmittance oracle: the fraction of a light's unoccluded intensity that reaches a
// world point through the scene, per colour channel, in double precision, on host and device.
//
//   T_c = prod over surface crossings strictly between light and point of the crossing rule's
//         T_c (engine/scene/surface_transmittance.h: 1 - alpha without glass; glass adds
//         transmission (1 - Fresnel) times its colour; a texture gives alpha and colour at
//         the crossing, engine/scene/texture_sampling.h)
//       * exp(-optical depth of channel c through constant interiors (exact chords, per channel:
//         sigma * sigma_tint) and volumes (grey))
//
// Its scalar answer is the luminance of T (Rec. 709 weights; a grey T is itself).
// Crossings come from a BVH walk along the ray from a point outside the scene through the
// light to the point, so objects that contain the light are known without a special case.
// Constant interiors use the order-free chord formula sum_i s_i (t_p - clamp(t_i, t_l, t_p))
// per channel with s_i = +1 entering, -1 leaving (closed meshes oriented outward). Volume
// interiors collect their crossings (at most kMaxVolumeCrossings per ray, overflow flagged), and
// integrate the transfer-mapped trilinear density over each inside interval in closed form, cell
// by cell, skipping bricks of zero extinction (engine/oracle/volume_chord.h).
//
// Conventions: a crossing within kOracleEndTolerance * (scene diagonal + segment length) of
// the point or the light is AT it, not between (a point exactly on a surface is not shadowed
// by that surface). Outside a spot cone T = 0; on the cone boundary the point is inside.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/hd.h"
#include "core/math.h"
#include "engine/oracle/volume_chord.h"
#include "engine/scene/ray_query.h"
#include "engine/scene/scene_view.h"
#include "engine/scene/surface_transmittance.h"
#include "engine/scene/volume_sampling.h"

namespace dv {

inline constexpr double kOracleEndTolerance = 1e-9;
inline constexpr int kMaxVolumeCrossings = 64;

enum OracleFlag : uint32_t {
  kOracleCrossingOverflow = 1u << 0,  // more volume crossings than kMaxVolumeCrossings
};

struct OracleResult {
  double transmittance;  // luminance(rgb)
  uint32_t flags;
  dvec3 rgb;  // per channel
};

DV_HD inline OracleResult oracle_result(const dvec3& rgb, uint32_t flags) {
  return {luminance(rgb), flags, rgb};
}

// The ray of one light/point query: from `origin` (outside every object) along unit `dir`;
// the light sits at t_light, the point at t_point.
struct LightSegment {
  dvec3 origin;
  dvec3 dir;
  double t_light;
  double t_point;
};

// Distance from x along unit w to where the ray leaves the box (negative if behind).
DV_HD inline double box_exit_distance(const Aabb& box, const dvec3& x, const dvec3& w) {
  double t = 1e300;
  for (int a = 0; a < 3; ++a) {
    if (w[a] > 0.0) t = min_value(t, (box.hi[a] - x[a]) / w[a]);
    if (w[a] < 0.0) t = min_value(t, (box.lo[a] - x[a]) / w[a]);
  }
  return t;
}

DV_HD inline Aabb padded_bounds(const SceneView& s) {
  const double pad = 1e-6 * s.diagonal + 1e-9;
  return {s.bounds.lo - dvec3(pad), s.bounds.hi + dvec3(pad)};
}

// Builds the query ray; returns false when the point is outside a spot light's cone.
DV_HD inline bool make_light_segment(const SceneView& s, const LightView& light, const dvec3& p,
                                     LightSegment& seg) {
  const Aabb box = padded_bounds(s);
  const double margin = 1e-3 * s.diagonal + 1e-6;
  if (light.type == LightType::directional) {
    const dvec3 to_light = -light.direction;
    const double d = max_value(box_exit_distance(box, p, to_light), 0.0) + margin;
    seg.origin = p + to_light * d;
    seg.dir = -to_light;
    seg.t_light = 0.0;
    seg.t_point = d;
    return true;
  }
  const dvec3 delta = p - light.position;
  const double len = glm::length(delta);
  if (len == 0.0) {
    seg = {p, dvec3(0.0, 0.0, 1.0), 0.0, 0.0};
    return true;
  }
  const dvec3 dir = delta / len;
  if (outside_spot_cone(light, dir)) return false;
  double back = 0.0;
  if (box.contains(light.position))
    back = max_value(box_exit_distance(box, light.position, -dir), 0.0) + margin;
  seg.origin = light.position - dir * back;
  seg.dir = dir;
  seg.t_light = back;
  seg.t_point = back + len;
  return true;
}

DV_HD inline OracleResult exact_transmittance(const SceneView& s, const LightView& light,
                                              const dvec3& p) {
  LightSegment seg;
  if (!make_light_segment(s, light, p, seg)) return oracle_result(dvec3(0.0), 0u);
  if (seg.t_point <= seg.t_light) return oracle_result(dvec3(1.0), 0u);
  const double eps = kOracleEndTolerance * (s.diagonal + (seg.t_point - seg.t_light));
  const double t_l = seg.t_light, t_p = seg.t_point;
  struct Crossing {
    double t;
    int32_t object;
    bool entering;
  };
  Crossing crossings[kMaxVolumeCrossings];
  int n_crossings = 0;
  uint32_t flags = 0;
  dvec3 surface(1.0), tau_constant(0.0);
  const ShearedRay ray = make_sheared_ray(seg.origin, seg.dir);
  for_each_hit(s, ray, 0.0, t_p + eps, [&](const RayHit& h) {
    const int32_t oi = int32_t(s.triangle_object[h.triangle]);
    const ObjectView& o = s.objects[oi];
    if (h.t > t_l + eps && h.t < t_p - eps)
      surface *= crossing_transmittance(s, o, h.triangle, seg.dir, seg.origin + seg.dir * h.t);
    const double sign = h.entering ? 1.0 : -1.0;
    if (o.interior == InteriorKind::constant) {
      tau_constant += o.sigma_rgb * (sign * (t_p - clamp_value(h.t, t_l, t_p)));
    } else if (o.interior == InteriorKind::volume) {
      if (n_crossings < kMaxVolumeCrossings)
        crossings[n_crossings++] = {h.t, oi, h.entering};
      else
        flags |= kOracleCrossingOverflow;
    }
    return true;
  });
  tau_constant = glm::max(tau_constant, dvec3(0.0));  // rounding of cancelling chords
  // Sort volume crossings by t (few per ray), then integrate each object's inside intervals.
  for (int i = 1; i < n_crossings; ++i) {
    Crossing c = crossings[i];
    int j = i - 1;
    while (j >= 0 && crossings[j].t > c.t) crossings[j + 1] = crossings[j], --j;
    crossings[j + 1] = c;
  }
  double tau_volume = 0.0;
  for (int i = 0; i < n_crossings; ++i) {
    const int32_t oi = crossings[i].object;
    bool first_of_object = true;
    for (int j = 0; j < i; ++j) first_of_object &= crossings[j].object != oi;
    if (!first_of_object) continue;
    const ObjectView& o = s.objects[oi];
    int depth = 0;
    double enter_t = 0.0;
    for (int j = i; j < n_crossings; ++j) {
      if (crossings[j].object != oi) continue;
      const int before = depth;
      depth += crossings[j].entering ? 1 : -1;
      if (before <= 0 && depth > 0) enter_t = crossings[j].t;
      if (before > 0 && depth <= 0) {
        const double a = clamp_value(enter_t, t_l, t_p), b = clamp_value(crossings[j].t, t_l, t_p);
        tau_volume += volume_optical_depth(s, o, seg.origin, seg.dir, a, b);
      }
    }
    if (depth > 0) {  // the point lies inside this volume
      const double a = clamp_value(enter_t, t_l, t_p);
      tau_volume += volume_optical_depth(s, o, seg.origin, seg.dir, a, t_p);
    }
  }
  const dvec3 tau = tau_constant + dvec3(tau_volume);
  return oracle_result(surface * dvec3(exp(-tau.x), exp(-tau.y), exp(-tau.z)), flags);
}

}  // namespace dv
