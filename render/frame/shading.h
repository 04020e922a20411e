// Phong shading (Knecht eq. 3.8/3.9) shared by every renderer, on host and device. The shadow
// term (RGB: tinted glass and media colour the light) multiplies both the diffuse and the specular
// term (eq. 3.9 as printed shadows only the specular: a typo). Cone fade and 1/d^2 falloff belong
// to the light's intensity at a point, never to its transmittance.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/bits.h"
#include "core/hd.h"
#include "core/math.h"
#include "engine/raster/shadow_receiver.h"
#include "engine/scene/scene_view.h"

namespace dv {

// Direction from p toward the light and the light's intensity arriving there, unshadowed.
struct LightArrival {
  dvec3 to_light;
  double intensity;
};

// Spot cone fade: KHR_lights_punctual's (for glTF lights: linear in the cosine between the
// outer and inner cone, squared) or deepvox's smoothstep over the penumbra. c = cos of the
// angle to the axis, inside the cone.
DV_HD inline double spot_fade(const LightView& l, double c) {
  if (l.gltf_cone) {
    const double width = max_value(l.cos_inner - l.cos_cutoff, 0.001);
    const double x = min_value(max_value((c - l.cos_cutoff) / width, 0.0), 1.0);
    return x * x;
  }
  if (l.cos_inner > l.cos_cutoff && c < l.cos_inner) {
    const double x = (c - l.cos_cutoff) / (l.cos_inner - l.cos_cutoff);
    return x * x * (3.0 - 2.0 * x);
  }
  return 1.0;
}

DV_HD inline LightArrival light_arrival(const LightView& l, const dvec3& p) {
  if (l.type == LightType::directional) return {-l.direction, l.intensity};
  const dvec3 d = l.position - p;
  const double dist2 = glm::dot(d, d);
  if (dist2 == 0.0) return {dvec3(0.0, 1.0, 0.0), 0.0};
  const dvec3 to_light = d / sqrt(dist2);
  double fade = 1.0;
  if (l.type == LightType::spot) {
    if (outside_spot_cone(l, -to_light)) return {to_light, 0.0};
    fade = spot_fade(l, -glm::dot(to_light, l.direction));
  }
  if (l.range > 0.0) {  // the spec's window: clamp(1 - (d / range)^4, 0, 1)
    const double r2 = dist2 / (l.range * l.range);
    fade *= max_value(1.0 - r2 * r2, 0.0);
  }
  return {to_light, l.intensity * fade / dist2};
}

// Phong colour of the point `at` (its shadow receiver: a surface point carries its geometric
// normal, a volume sample none) with unit shading normal n (facing the viewer) or n = 0 for
// unoriented volume samples (then the diffuse term takes no angle and there is no highlight).
// With `highlight_only` just the specular highlights (what a transmissive surface shows). The
// lights are those of `lights` (the scene's, where they are or a block's copy) that light_mask
// lists (its tile's, engine/raster/light_tiles.h), in ascending order, or every light when it
// is nullptr. kListed compiles the loop over a mask's words and their set bits, which a pass
// with light lists runs; without, the plain loop over every light (light_mask must be null).
// Each is the faster where it runs (results/perf/2026-12-06-shared-tables, an H200):
// knecht-32-lights' shadow-map pass at 720x480 takes 12.2-12.9 ms with the word loop and
// 30.4-31.9 ms with a loop that takes one light per step (a counter, or the mask's next bit),
// while knecht-fig56's one-light passes are 2-4 % faster with the plain loop.
template <bool kListed, class Source>
DV_HD dvec3 shade_phong(View<const LightView> lights, const Source& shadows,
                        typename Source::Cursor& cursor, const uint32_t* light_mask,
                        const ObjectView& o, const dvec3& color, const ShadowReceiver& at,
                        const dvec3& n, const dvec3& to_eye, bool highlight_only = false) {
  if (highlight_only && !(o.specular > 0.0 && glm::dot(n, n) > 0.0)) return dvec3(0.0);
  const dvec3& p = at.point;
  dvec3 out = highlight_only ? dvec3(0.0) : o.ambient * color;
  const bool oriented = glm::dot(n, n) > 0.0;
  const auto add_light = [&](int li) {
    const LightView& l = lights[li];
    const LightArrival a = light_arrival(l, p);
    if (a.intensity <= 0.0) return;
    const double n_dot_l = oriented ? glm::dot(n, a.to_light) : 1.0;
    if (n_dot_l <= 0.0) return;
    const dvec3 t = shadows.transmittance_rgb(cursor, at, li);
    if (max_value(t.x, max_value(t.y, t.z)) <= 0.0) return;
    double spec = 0.0;
    if (oriented && o.specular > 0.0) {
      const dvec3 r = 2.0 * n_dot_l * n - a.to_light;
      const double r_dot_v = glm::dot(r, to_eye);
      if (r_dot_v > 0.0) spec = o.specular * pow(r_dot_v, o.shininess);
    }
    if (highlight_only)
      out += l.color * (a.intensity * t) * spec;
    else
      out += l.color * (a.intensity * t) * (o.diffuse * n_dot_l * color + dvec3(spec));
  };
  const int count = int(lights.size);
  if constexpr (kListed) {
    for (int first = 0; first < count; first += 32) {
      uint32_t listed = light_mask ? light_mask[first / 32] : bits_below(~0u, count - first);
      while (listed != 0u) {
        const int li = first + lowest_bit(listed);
        listed &= listed - 1u;
        add_light(li);
      }
    }
  } else {
    for (int li = 0; li < count; ++li) add_light(li);
  }
  return out;
}

}  // namespace dv
