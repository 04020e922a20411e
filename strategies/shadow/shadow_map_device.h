// Kernel side of the conventional depth shadow map (Williams 1978; Brabec 2003 ch. 4-5): per
// light one face (spot: perspective over the cone; directional: orthographic fitted to the
// casters) or six 90-degree faces (omni), each a square map of the nearest caster's depth.
// A point is lit where its own depth, less the receiver bias, does not exceed the stored depth
// (light_faces.h, receiver_depth: for surface points a constant plus `slope_bias` texel sizes
// times the receiver's tangent to the light, over the PCF kernel's reach; none elsewhere); PCF
// averages that test over pcf x pcf texels around the point's projection (Reeves et al.:
// compare, then filter). Every surface whose caster opacity reaches kDepthMapOpaqueAlpha
// (depth_maps.h: its alpha at that point, or an interior medium's opacity across the object)
// casts a full shadow, the others none: this is the opaque-shadow baseline. Glass the depths
// leave out (transmission > 0) is kept, for scenes that have it, in a glass layer: a receiver
// beyond a texel's nearest glass crossing gets the product of the crossing rule
// (engine/scene/surface_transmittance.h) over the texel ray's glass crossings, one layer per
// texel (the translucent shadow maps of real-time engines), per colour channel. Host and device
// code.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "cuda/buffer.h"
#include "engine/raster/light_faces.h"
#include "engine/raster/shadow_receiver.h"
#include "engine/scene/scene_view.h"
#include "engine/scene/surface_transmittance.h"

namespace dv {

struct ShadowMapSource {
  View<const LightView> lights;
  View<const ShadowLight> light_faces;
  View<const ShadowFace> faces;
  View<const float> depths;  // +inf where no caster
  int resolution;
  int pcf;            // kernel side in texels (1: a single nearest-texel test)
  double bias;        // world units subtracted from a surface point's depth ...
  double slope_bias;  // ... plus this many texel sizes x tan(angle to the light) per reach
  // The glass layer (only for scenes with glass the depths leave out; empty otherwise): per
  // texel the nearest glass crossing's depth (+inf: none) and the product of the crossing rule
  // over the texel ray's glass crossings.
  View<const float> glass_depths{};
  View<const vec3> glass_filters{};

  struct Cursor {
    uint32_t flags = 0;
  };

  DV_HD double transmittance(Cursor& cursor, const ShadowReceiver& r, int light) const {
    return luminance(transmittance_rgb(cursor, r, light));
  }

  DV_HD dvec3 transmittance_rgb(Cursor&, const ShadowReceiver& r, int light) const {
    const dvec3& p = r.point;
    const LightView& l = lights[light];
    if (outside_light_cone(l, p)) return dvec3(0.0);
    const ShadowFace& f = faces[face_of(light_faces[light], l, p)];
    FacePoint fp;
    if (!project_to_face(f, resolution, p, fp)) return dvec3(1.0);
    const double depth = receiver_depth(f, r, fp.depth, bias, slope_bias, 0.5 * double(pcf + 1));
    const double lit = lit_fraction(f, fp, depth);
    if (glass_filters.empty() || lit == 0.0) return dvec3(lit);
    return lit * glass_filter(f, fp, depth);
  }

  // The PCF kernel's share of texels whose nearest caster lies at or beyond `depth`.
  DV_HD double lit_fraction(const ShadowFace& f, const FacePoint& fp, double depth) const {
    const int x0 = int(floor(fp.u - 0.5 * (pcf - 1) + 0.5)),
              y0 = int(floor(fp.v - 0.5 * (pcf - 1) + 0.5));
    int lit = 0, taps = 0;
    for (int j = 0; j < pcf; ++j)
      for (int i = 0; i < pcf; ++i) {
        const int x = x0 + i, y = y0 + j;
        if (x < 0 || y < 0 || x >= resolution || y >= resolution) continue;  // outside: lit
        ++taps;
        lit += depth <= double(depths[f.offset + int64_t(y) * resolution + x]);
      }
    return taps ? double(lit + (pcf * pcf - taps)) / double(pcf * pcf) : 1.0;
  }

  // The nearest texel's glass filter for a receiver beyond its nearest glass crossing, else 1.
  DV_HD dvec3 glass_filter(const ShadowFace& f, const FacePoint& fp, double depth) const {
    const int x = int(floor(fp.u + 0.5)), y = int(floor(fp.v + 0.5));
    if (x < 0 || y < 0 || x >= resolution || y >= resolution) return dvec3(1.0);
    const int64_t texel = f.offset + int64_t(y) * resolution + x;
    return depth > double(glass_depths[texel]) ? dvec3(glass_filters[texel]) : dvec3(1.0);
  }
};

}  // namespace dv
