// The camera pass's payload for the fragment walk: Phong-shaded translucent surfaces and
// volume samples composited front to back (Knecht eq. 3.10/3.11), constant media absorbing
// exactly, the shadow term of every shaded sample from a shadow source. Host and device code.
#pragma once

#include <cmath>

#include "core/hd.h"
#include "renderer/fragment_walk.h"
#include "renderer/shading.h"
#include "scene/volume_sampling.h"

namespace dv {

// Opacity at which a ray stops: what is behind contributes less than this fraction.
inline constexpr double kSaturatedTransmittance = 1e-6;

template <class Source>
struct ShadePayload {
  const SceneView& s;
  const Source& shadows;
  dvec3 origin;
  dvec3 dir;
  typename Source::Cursor cursor{};
  dvec3 color{0.0};
  double transmittance = 1.0;
  unsigned long long samples = 0;

  DV_HD bool done() const { return transmittance <= kSaturatedTransmittance; }

  // A translucent surface: its Phong colour over what lies behind, weighted by its opacity.
  DV_HD void surface(const RayHit& h, int32_t object) {
    const ObjectView& o = s.objects[object];
    if (o.alpha <= 0.0) return;
    const u32vec3 tri = s.triangles[h.triangle];
    const dvec3 p0 = s.vertices[tri.x], p1 = s.vertices[tri.y], p2 = s.vertices[tri.z];
    dvec3 n = glm::cross(p1 - p0, p2 - p0);
    const double len = glm::length(n);
    n = len > 0.0 ? n / len : -dir;
    if (glm::dot(n, dir) > 0.0) n = -n;  // two-sided: face the viewer
    const dvec3 c = shade_phong(s, shadows, cursor, o, o.color, origin + dir * h.t, n, -dir);
    color += transmittance * o.alpha * c;
    transmittance *= 1.0 - o.alpha;
  }

  // Media over [t0, t1]: constant ones only absorb (exact exp of the chord); volumes are sampled
  // at step midpoints with the smallest step of those the ray is inside, the last step shortened.
  DV_HD void segment(const InsideSet& inside, double t0, double t1) {
    double sigma_constant = 0.0, step = 1e300;
    bool any_volume = false;
    for (int i = 0; i < inside.count; ++i) {
      const ObjectView& o = s.objects[inside.object[i]];
      if (o.interior == InteriorKind::constant) sigma_constant += o.sigma;
      if (o.interior == InteriorKind::volume) any_volume = true, step = min_value(step, o.step);
    }
    if (!any_volume) {
      transmittance *= exp(-sigma_constant * (t1 - t0));
      return;
    }
    const int64_t steps = int64_t(ceil((t1 - t0) / step));
    for (int64_t k = 0; k < steps && !done(); ++k) {
      const double a = t0 + double(k) * step, b = min_value(a + step, t1);
      const double mid = 0.5 * (a + b);
      const double empty_until = empty_run_end(inside, mid);
      if (empty_until > mid) {
        // Samples whose midpoints lie in empty bricks of every volume would add nothing but the
        // constant media's absorption: jump over them.
        const int64_t last = min_value(steps - 1, int64_t(floor((empty_until - t0) / step - 0.5)));
        const int64_t skip_to = last > k ? last : k;
        transmittance *=
            exp(-sigma_constant * (min_value(t0 + double(skip_to + 1) * step, t1) - a));
        k = skip_to;
        continue;
      }
      volume_sample(inside, sigma_constant, origin + dir * mid, b - a);
    }
  }

  // The ray parameter up to which every volume the ray is inside stays in empty bricks, from
  // the sample at t; t itself when some volume is not empty there.
  DV_HD double empty_run_end(const InsideSet& inside, double t) const {
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

  // One volume sample of length dt at x: alpha = 1 - exp(-sigma * dt), emission from the volumes'
  // share of the extinction, shaded with the dominant volume's density gradient as normal (the
  // exact gradient of the trilinear interpolant: the same eight samples, no extra lookups).
  DV_HD void volume_sample(const InsideSet& inside, double sigma_constant, const dvec3& x,
                           double dt) {
    double sigma_volume = 0.0, strongest = 0.0;
    dvec3 weighted_color(0.0), gradient(0.0);
    int32_t dominant = -1;
    for (int i = 0; i < inside.count; ++i) {
      const ObjectView& o = s.objects[inside.object[i]];
      if (o.interior != InteriorKind::volume) continue;
      const GridCell cell = grid_cell(s, s.volumes[o.volume], world_to_grid(o, x));
      const TransferSample ts = apply_transfer(s, o, trilinear(cell));
      sigma_volume += ts.sigma;
      weighted_color += ts.sigma * ts.color;
      if (ts.sigma > strongest) {
        strongest = ts.sigma, dominant = inside.object[i];
        gradient = world_gradient(o, trilinear_gradient(cell));
      }
    }
    ++samples;
    const double sigma = sigma_constant + sigma_volume;
    if (sigma <= 0.0) return;
    const double alpha = 1.0 - exp(-sigma * dt);
    if (dominant >= 0) {
      const ObjectView& o = s.objects[dominant];
      dvec3 n = gradient;
      const double len = glm::length(n);
      n = len > 1e-12 ? -n / len : dvec3(0.0);
      if (glm::dot(n, dir) > 0.0) n = -n;
      const dvec3 c = shade_phong(s, shadows, cursor, o, weighted_color / sigma_volume, x, n, -dir);
      color += transmittance * alpha * (sigma_volume / sigma) * c;
    }
    transmittance *= 1.0 - alpha;
  }
};

}  // namespace dv
