// The camera pass's payload for the fragment walk: Phong-shaded translucent surfaces and
// volume samples composited front to back (Knecht eq. 3.10/3.11), constant media absorbing
// exactly, the shadow term of every shaded sample from a shadow source. Host and device code.
// What the camera sees through things is RGB and follows the crossing rule the shadows follow
// (engine/scene/surface_transmittance.h): transmissive surfaces pass (1 - F) of their glass part
// tinted by their colour, constant media absorb per channel; the shadow term is RGB too.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/hd.h"
#include "core/lane_group.h"
#include "engine/raster/fragment_walk.h"
#include "engine/raster/media_march.h"
#include "engine/scene/surface_transmittance.h"
#include "engine/scene/volume_sampling.h"
#include "render/frame/shading.h"

namespace dv {

// Opacity at which a ray stops: what is behind contributes less than this fraction.
inline constexpr double kSaturatedTransmittance = 1e-6;

// The lights a payload shades with: with tile light lists a view of its own (the scene's
// lights, or a block's copy of them in shared memory), without them the scene's.
template <bool kTiledLights>
struct ShadingLights {
  View<const LightView> table;
  DV_HD View<const LightView> of(const SceneView&) const { return table; }
};
template <>
struct ShadingLights<false> {
  DV_HD View<const LightView> of(const SceneView& s) const { return s.lights; }
};

template <bool kTiledLights>
DV_HD ShadingLights<kTiledLights> scene_shading_lights(const SceneView& s) {
  if constexpr (kTiledLights)
    return {s.lights};
  else
    return {};
}

// The surface looks a payload is compiled for: every kind (base-colour and emissive textures,
// glass, emission), or only plain ones (plain_look), for which it compiles without the texture,
// glass and emission code (its code holds one Phong evaluation per surface crossing, not two) and
// gives the bits of the general payload. A pass picks it at launch when every object of the scene
// is plain (results/perf/2026-12-06-plain-looks).
enum class SurfaceLooks : uint8_t { any, plain };

// Untextured, without transmission and not emitting: a grey scene's surfaces.
DV_HD inline bool plain_look(const ObjectView& o) {
  return o.texture < 0 && o.emissive_texture < 0 && o.transmission <= 0.0 && o.emission.x == 0.0 &&
         o.emission.y == 0.0 && o.emission.z == 0.0;
}

// kTiledLights: whether pixels shade their tile's light list (light_mask); a payload without
// one compiles to the plain loop over every light. kLooks: the surfaces it can meet.
template <class Source, bool kTiledLights = true, SurfaceLooks kLooks = SurfaceLooks::any>
struct ShadePayload {
  const SceneView& s;
  const Source& shadows;
  dvec3 origin;
  dvec3 dir;
  ShadingLights<kTiledLights> lights = scene_shading_lights<kTiledLights>(s);
  typename Source::Cursor cursor{};
  dvec3 color{0.0};
  dvec3 transmittance{1.0};
  unsigned long long samples = 0;
  dvec3 segment_sigma_rgb{0.0};          // the constant media's extinction in the current segment
  LaneGroup lanes{};                     // lanes that split this pixel's volume steps between them
  dvec3 transmittance_scale{1.0};        // while marching a share: the transmittance before it
  const uint32_t* light_mask = nullptr;  // the pixel's tile's lights (light_tiles.h); null: all

  DV_HD static bool saturated(const dvec3& t) {
    return max_value(t.x, max_value(t.y, t.z)) <= kSaturatedTransmittance;
  }

  DV_HD bool done() const { return saturated(transmittance * transmittance_scale); }

  DV_HD const uint32_t* listed_lights() const {
    if constexpr (kTiledLights)
      return light_mask;
    else
      return nullptr;
  }

  // A translucent surface: its Phong colour over what lies behind, weighted by its opacity;
  // its transmissive part adds highlights and reflects, by the Fresnel reflectance F at the
  // viewing angle, an ambient environment of level o.ambient (so clear glass shows a bright rim
  // on any background), its emission (times its emissive texture's texel) adds where it
  // covers, and it lets through what the
  // crossing rule says. The shaded
  // point is the crossing moved onto its triangle (a rasterized crossing can lie just outside
  // it, on the plane's extension behind a neighbour, and would shadow itself), and its shadow
  // receiver carries the geometric normal; shading uses the interpolated vertex normal, and a
  // textured surface its texel's colour and coverage (engine/scene/texture_sampling.h). A
  // plain surface (kLooks) only adds its Phong colour and lets through 1 - alpha.
  DV_HD void surface(const RayHit& h, int32_t object) {
    const ObjectView& o = s.objects[object];
    if (o.alpha <= 0.0 && o.transmission <= 0.0) return;
    const u32vec3 tri = s.triangles[h.triangle];
    const dvec3 p0 = s.vertices[tri.x], p1 = s.vertices[tri.y], p2 = s.vertices[tri.z];
    const dvec3 point = nearest_point_on_triangle(origin + dir * h.t, p0, p1, p2);
    const SurfaceLook look = kLooks == SurfaceLooks::plain
                                 ? SurfaceLook{o.alpha, o.transmission, o.color}
                                 : surface_look(s, o, h.triangle, point);
    if (look.alpha <= 0.0 && look.transmission <= 0.0) return;
    dvec3 n = glm::cross(p1 - p0, p2 - p0);
    const double len = glm::length(n);
    n = len > 0.0 ? n / len : -dir;
    if (glm::dot(n, dir) > 0.0) n = -n;  // two-sided: face the viewer
    const ShadowReceiver at{point, n};
    const dvec3 shading = shading_normal(s, h.triangle, point, n);
    if (look.alpha > 0.0) {
      const dvec3 c = shade_phong<kTiledLights>(lights.of(s), shadows, cursor, listed_lights(), o,
                                                look.color, at, shading, -dir);
      color += transmittance * look.alpha * c;
    }
    if constexpr (kLooks == SurfaceLooks::plain) {
      transmittance *= 1.0 - (look.alpha + look.transmission);
      return;
    }
    const double cos_to_normal = glm::dot(n, dir);
    if (look.transmission > 0.0) {
      const dvec3 highlight = shade_phong<kTiledLights>(
          lights.of(s), shadows, cursor, listed_lights(), o, look.color, at, shading, -dir, true);
      const double reflected = fresnel_schlick(o.ior, cos_to_normal) * o.ambient;
      color += transmittance * look.transmission * (highlight + dvec3(reflected));
    }
    color += transmittance * (look.alpha + look.transmission) *
             surface_emission(s, o, h.triangle, point);
    transmittance *=
        surface_transmittance(o, cos_to_normal, look.alpha + look.transmission, look.color);
  }

  // Media over [t0, t1], stepped by march_media (engine/raster/media_march.h); volume steps in
  // shares when lanes split them.
  DV_HD void segment(const InsideSet& inside, double t0, double t1) {
    segment_sigma_rgb = constant_extinction_rgb(s, inside);
    if (lanes.count > 1 && has_volume(s, inside)) return segment_in_shares(inside, t0, t1);
    march_media(s, inside, origin, dir, t0, t1, *this);
  }

  // What one share of a segment's steps adds, composited from clear (colour 0, transmittance 1).
  struct SharePart {
    dvec3 color;
    dvec3 transmittance;
    unsigned long long samples;
  };

  // The segment's steps in lanes.count contiguous shares, each composited from clear (a share
  // stops where the ray is saturated even if the shares before it were clear), then folded in
  // order: what a share adds is kept only while the ray before it is not saturated. In device
  // code each lane of the group marches its own share and the lanes exchange the parts; a CPU
  // thread marches every share itself. Both fold the same parts in the same order.
  DV_HD void segment_in_shares(const InsideSet& inside, double t0, double t1) {
    const dvec3 color_before = color, transmittance_before = transmittance;
    const unsigned long long samples_before = samples;
    const auto march_share = [&](int part) {
      color = dvec3(0.0), transmittance = dvec3(1.0), samples = 0;
      transmittance_scale = transmittance_before;
      march_media(s, inside, origin, dir, t0, t1, *this, 1.0, StepShare{part, lanes.count});
      return SharePart{color, transmittance, samples};
    };
#if DV_IN_DEVICE_CODE
    const SharePart mine = march_share(lanes.rank);
#endif
    dvec3 folded_color = color_before, folded_transmittance = transmittance_before;
    unsigned long long folded_samples = samples_before;
    for (int part = 0; part < lanes.count; ++part) {
#if DV_IN_DEVICE_CODE
      const SharePart p{lane_value(lanes, mine.color, part),
                        lane_value(lanes, mine.transmittance, part),
                        lane_value(lanes, mine.samples, part)};
      cursor.flags |= lane_value(lanes, cursor.flags, part);
#else
      const SharePart p = march_share(part);
#endif
      folded_samples += p.samples;
      if (saturated(folded_transmittance)) continue;
      folded_color += folded_transmittance * p.color;
      folded_transmittance *= p.transmittance;
    }
    color = folded_color, transmittance = folded_transmittance, samples = folded_samples;
    transmittance_scale = dvec3(1.0);
  }

  // exp(-sigma * length) per channel; grey media (equal channels, the common case) take one
  // exponential for all three, which gives the same bits.
  DV_HD static dvec3 attenuation(const dvec3& sigma, double length) {
    if (sigma.x == sigma.y && sigma.y == sigma.z) return dvec3(exp(-sigma.x * length));
    return dvec3(exp(-sigma.x * length), exp(-sigma.y * length), exp(-sigma.z * length));
  }

  // Constant media only over [a, b]: they absorb, exactly, per channel.
  DV_HD void absorb(double, double a, double b) {
    transmittance *= attenuation(segment_sigma_rgb, b - a);
  }

  DV_HD void sample(const InsideSet& inside, double, const dvec3& x, double a, double b) {
    volume_sample(inside, segment_sigma_rgb, x, b - a);
  }

  // One volume sample of length dt at x: alpha = 1 - exp(-sigma * dt), emission from the volumes'
  // share of the extinction, shaded with the dominant volume's density gradient as normal (the
  // exact gradient of the trilinear interpolant: the same eight samples, no extra lookups).
  DV_HD void volume_sample(const InsideSet& inside, const dvec3& sigma_constant, const dvec3& x,
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
    const dvec3 sigma = sigma_constant + sigma_volume;
    if (max_value(sigma.x, max_value(sigma.y, sigma.z)) <= 0.0) return;
    const dvec3 alpha = 1.0 - attenuation(sigma, dt);
    if (dominant >= 0) {
      const ObjectView& o = s.objects[dominant];
      dvec3 n = gradient;
      const double len = glm::length(n);
      n = len > 1e-12 ? -n / len : dvec3(0.0);
      if (glm::dot(n, dir) > 0.0) n = -n;
      const ShadowReceiver at{x};  // a medium point: no surface bias
      const dvec3 c = shade_phong<kTiledLights>(lights.of(s), shadows, cursor, listed_lights(), o,
                                                weighted_color / sigma_volume, at, n, -dir);
      color += transmittance * alpha * (sigma_volume / sigma) * c;
    }
    transmittance *= 1.0 - alpha;
  }
};

}  // namespace dv
