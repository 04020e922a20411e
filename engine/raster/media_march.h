// Stepping through the media a ray is inside over one segment [t0, t1] between crossings, with
// the step rules every pass shares (the camera pass composites colour, the deep-shadow-map pass
// records visibility): constant media alone are handed over whole (their absorption is exact),
// volumes are sampled at step midpoints with the smallest step of those the ray is inside, the
// last step shortened, and runs of samples whose midpoints lie in empty bricks of every volume
// are jumped over (they would add nothing but the constant media's absorption). Host and device.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/hd.h"
#include "core/math.h"
#include "engine/raster/fragment_walk.h"
#include "engine/scene/volume_sampling.h"

namespace dv {

// The ray parameter up to which every volume the ray is inside stays in empty bricks, from the
// sample at t; t itself when some volume is not empty there.
DV_HD inline double empty_run_end(const SceneView& s, const InsideSet& inside, const dvec3& origin,
                                  const dvec3& dir, double t) {
  double until = 1e300;
  const dvec3 x = origin + dir * t;
  for (int i = 0; i < inside.count; ++i) {
    const ObjectView& o = s.objects[inside.object[i]];
    if (o.interior != InteriorKind::volume) continue;
    const dvec3 g = world_to_grid(o, x);
    ivec3 brick;
    if (!in_empty_brick(s, o, g, brick)) return t;
    const dvec3 gd = dvec3(o.world_to_grid * dvec4(dir, 0.0));
    until = min_value(until, t + brick_exit_distance(o, brick, g, gd));
  }
  return until;
}

// Whether the ray is inside a volume (then its segments are sampled in steps).
DV_HD inline bool has_volume(const SceneView& s, const InsideSet& inside) {
  for (int i = 0; i < inside.count; ++i)
    if (s.objects[inside.object[i]].interior == InteriorKind::volume) return true;
  return false;
}

// Which of a segment's steps one march takes: share `part` of `parts` contiguous shares of its
// steps (lanes that split a ray's samples between them, render/frame/shade_payload.h); all by
// default.
struct StepShare {
  int part = 0;
  int parts = 1;
};

// Visitor interface:
//   bool done() const;                                         stop early
//   void absorb(double sigma_constant, double a, double b);    constant media only over [a, b]
//   void sample(const InsideSet&, double sigma_constant, const dvec3& x, double a, double b);
//                                                              one volume step [a, b], midpoint x
// `step_scale` multiplies the volumes' steps (accuracy studies; 1 everywhere else). With a share,
// steps k of [steps * part / parts, steps * (part + 1) / parts) only, placed as in a whole march.
template <class Visitor>
DV_HD void march_media(const SceneView& s, const InsideSet& inside, const dvec3& origin,
                       const dvec3& dir, double t0, double t1, Visitor& visitor,
                       double step_scale = 1.0, StepShare share = {}) {
  double sigma_constant = 0.0, step = 1e300;
  bool any_volume = false;
  for (int i = 0; i < inside.count; ++i) {
    const ObjectView& o = s.objects[inside.object[i]];
    if (o.interior == InteriorKind::constant) sigma_constant += o.sigma;
    if (o.interior == InteriorKind::volume) any_volume = true, step = min_value(step, o.step);
  }
  if (!any_volume) {
    visitor.absorb(sigma_constant, t0, t1);
    return;
  }
  step *= step_scale;
  const int64_t steps = int64_t(ceil((t1 - t0) / step));
  const int64_t k_end = steps * (share.part + 1) / share.parts;
  for (int64_t k = steps * share.part / share.parts; k < k_end && !visitor.done(); ++k) {
    const double a = t0 + double(k) * step, b = min_value(a + step, t1);
    const double mid = 0.5 * (a + b);
    const double empty_until = empty_run_end(s, inside, origin, dir, mid);
    if (empty_until > mid) {
      const int64_t last = min_value(k_end - 1, int64_t(floor((empty_until - t0) / step - 0.5)));
      const int64_t skip_to = last > k ? last : k;
      visitor.absorb(sigma_constant, a, min_value(t0 + double(skip_to + 1) * step, t1));
      k = skip_to;
      continue;
    }
    visitor.sample(inside, sigma_constant, origin + dir * mid, a, b);
  }
}

// The per-channel extinction of the constant media the ray is inside (the camera pass and the
// DSM's colour side channel tint by it; march_media steps by the scalar sigma, summed in the same
// order).
DV_HD inline dvec3 constant_extinction_rgb(const SceneView& s, const InsideSet& inside) {
  dvec3 sigma(0.0);
  for (int i = 0; i < inside.count; ++i) {
    const ObjectView& o = s.objects[inside.object[i]];
    if (o.interior == InteriorKind::constant) sigma += o.sigma_rgb;
  }
  return sigma;
}

// The extinction of the volumes the ray is inside at x (constant media not included).
DV_HD inline double volume_extinction(const SceneView& s, const InsideSet& inside, const dvec3& x) {
  double sigma = 0.0;
  for (int i = 0; i < inside.count; ++i) {
    const ObjectView& o = s.objects[inside.object[i]];
    if (o.interior != InteriorKind::volume) continue;
    const GridCell cell = grid_cell(s, s.volumes[o.volume], world_to_grid(o, x));
    sigma += apply_transfer(s, o, trilinear(cell)).sigma;
  }
  return sigma;
}

}  // namespace dv
