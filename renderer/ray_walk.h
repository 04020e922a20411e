// The per-pixel walk of the reference renderer (see reference_render.h), host and device code.
#pragma once

#include <cmath>

#include "core/atomic.h"
#include "core/hd.h"
#include "oracle/transmittance.h"
#include "renderer/camera_rays.h"
#include "renderer/reference_render.h"
#include "renderer/shading.h"
#include "scene/ray_query.h"
#include "scene/volume_sampling.h"

namespace dv {

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
    if (!entering) return;  // leaving a medium we never entered: a crossing behind the walk start
    if (count == kMaxInsideObjects) {
      overflow = true;
      return;
    }
    object[count] = id, depth[count] = 1, ++count;
  }
};

struct PixelState {
  dvec3 color{0.0};
  double transmittance = 1.0;
  unsigned long long samples = 0;
};

// Composites the media of `inside` over the ray interval [t0, t1].
template <class Source>
DV_HD void composite_media(const SceneView& s, const Source& shadows, typename Source::Cursor& cursor,
                           const InsideSet& inside, const dvec3& origin, const dvec3& dir, double t0,
                           double t1, PixelState& px) {
  double sigma_constant = 0.0, step = 1e300;
  bool any_volume = false;
  for (int i = 0; i < inside.count; ++i) {
    const ObjectView& o = s.objects[inside.object[i]];
    if (o.interior == InteriorKind::constant) sigma_constant += o.sigma;
    if (o.interior == InteriorKind::volume) any_volume = true, step = min_value(step, o.step);
  }
  if (!any_volume) {
    px.transmittance *= exp(-sigma_constant * (t1 - t0));
    return;
  }
  const int64_t steps = int64_t(ceil((t1 - t0) / step));
  for (int64_t k = 0; k < steps && px.transmittance > 1e-6; ++k) {
    const double a = t0 + double(k) * step, b = min_value(a + step, t1);
    const dvec3 x = origin + dir * (0.5 * (a + b));
    double sigma_volume = 0.0, strongest = 0.0;
    dvec3 weighted_color(0.0);
    int32_t dominant = -1;
    for (int i = 0; i < inside.count; ++i) {
      const ObjectView& o = s.objects[inside.object[i]];
      if (o.interior != InteriorKind::volume) continue;
      const VolumeView& v = s.volumes[o.volume];
      const TransferSample ts = apply_transfer(s, o, density_at_grid(s, v, world_to_grid(o, x)));
      sigma_volume += ts.sigma;
      weighted_color += ts.sigma * ts.color;
      if (ts.sigma > strongest) strongest = ts.sigma, dominant = inside.object[i];
    }
    ++px.samples;
    const double sigma = sigma_constant + sigma_volume;
    if (sigma <= 0.0) continue;
    const double alpha = 1.0 - exp(-sigma * (b - a));
    if (dominant >= 0) {
      const ObjectView& o = s.objects[dominant];
      dvec3 n = density_gradient(s, o, x);
      const double len = glm::length(n);
      n = len > 1e-12 ? -n / len : dvec3(0.0);
      if (glm::dot(n, dir) > 0.0) n = -n;
      const dvec3 c = shade_phong(s, shadows, cursor, o, weighted_color / sigma_volume, x, n, -dir);
      px.color += px.transmittance * alpha * (sigma_volume / sigma) * c;
    }
    px.transmittance *= 1.0 - alpha;
  }
}

template <class Source>
DV_HD dvec3 walk_pixel(const SceneView& s, const CameraView& cam, const Source& shadows, int x, int y,
                       const dvec3& background, RenderCounters* counters) {
  const dvec3 dir = camera_ray_direction(cam, x, y);
  // Start outside the scene so the media containing the eye are found by their crossings.
  const Aabb box = padded_bounds(s);
  double t_eye = 0.0;
  if (box.contains(cam.position))
    t_eye = max_value(box_exit_distance(box, cam.position, -dir), 0.0) + 1e-3 * s.diagonal + 1e-6;
  const dvec3 origin = cam.position - dir * t_eye;
  const double t_near = t_eye + cam.near_plane / glm::dot(dir, cam.forward);
  const ShearedRay ray = make_sheared_ray(origin, dir);
  typename Source::Cursor cursor{};
  InsideSet inside;
  PixelState px;
  double t_prev = 0.0;
  int64_t tri_prev = -1;
  unsigned long long hits = 0;
  bool overflow = false;
  const double t_far = t_eye + max_value(box_exit_distance(box, cam.position, dir), 0.0);
  while (px.transmittance > 1e-6) {
    if (hits == kMaxHitsPerPixel) {
      overflow = true;
      break;
    }
    RayHit h;
    const bool found = next_hit(s, ray, t_prev, tri_prev, 1e300, h);
    const double t_end = found ? h.t : t_far;
    const double t_start = max_value(t_prev, t_near);
    if (inside.count > 0 && t_end > t_start)
      composite_media(s, shadows, cursor, inside, origin, dir, t_start, t_end, px);
    if (!found) break;
    ++hits;
    const int32_t oi = int32_t(s.triangle_object[h.triangle]);
    const ObjectView& o = s.objects[oi];
    if (h.t >= t_near && o.alpha > 0.0 && px.transmittance > 1e-6) {
      const u32vec3 tri = s.triangles[h.triangle];
      const dvec3 p0 = s.vertices[tri.x], p1 = s.vertices[tri.y], p2 = s.vertices[tri.z];
      dvec3 n = glm::cross(p1 - p0, p2 - p0);
      const double len = glm::length(n);
      n = len > 0.0 ? n / len : -dir;
      if (glm::dot(n, dir) > 0.0) n = -n;  // two-sided: face the viewer
      const dvec3 p = origin + dir * h.t;
      const dvec3 c = shade_phong(s, shadows, cursor, o, o.color, p, n, -dir);
      px.color += px.transmittance * o.alpha * c;
      px.transmittance *= 1.0 - o.alpha;
    }
    if (o.interior != InteriorKind::none) inside.cross(oi, h.entering);
    t_prev = h.t;
    tri_prev = h.triangle;
  }
  if (counters) {
    atomic_add(&counters->hits, hits);
    atomic_add(&counters->volume_samples, px.samples);
    atomic_max(&counters->max_hits, hits);
    if (overflow || inside.overflow) atomic_add(&counters->overflow_pixels, 1ull);
    if (cursor.flags) atomic_add(&counters->oracle_flag_pixels, 1ull);
  }
  return px.color + px.transmittance * background;
}

}  // namespace dv
