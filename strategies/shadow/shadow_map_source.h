// Kernel side of the conventional depth shadow map (Williams 1978; Brabec 2003 ch. 4-5): per
// light one face (spot: perspective over the cone; directional: orthographic fitted to the
// casters) or six 90-degree faces (omni), each a square map of the nearest caster's depth.
// A point is lit where its own depth, less the bias, does not exceed the stored depth (the bias
// is a constant plus a number of texel sizes at the point's depth, widened with the PCF
// kernel, since the lookup knows no surface normal); PCF
// averages that test over pcf x pcf texels around the point's projection (Reeves et al.:
// compare, then filter). Every surface with alpha > 0 casts a full shadow; media are not
// represented: this is the opaque-shadow baseline. Host and device code.
#pragma once

#include <cstdint>

#include "core/buffer.h"
#include "core/hd.h"
#include "renderer/raster/raster_projection.h"
#include "scene/scene_view.h"

namespace dv {

struct ShadowFace {
  RasterProjection projection;  // world -> clip of this face, res x res texels
  dvec3 eye;                    // perspective: the light; orthographic: a point on the axis
  dvec3 axis;                   // unit viewing direction
  bool orthographic;
  double texel_size;  // world size of a texel: per unit depth (perspective) or absolute
  int64_t offset;     // first texel in ShadowMapSource::depths
};

// Depth that the map stores and compares: distance from the light (perspective faces) or along
// the axis from `eye` (orthographic faces).
DV_HD inline double shadow_depth(const ShadowFace& f, const dvec3& x) {
  return f.orthographic ? glm::dot(x - f.eye, f.axis) : glm::length(x - f.eye);
}

struct ShadowLight {
  int32_t first_face;
  int32_t face_count;  // 1 (spot, directional) or 6 (omni)
};

struct ShadowMapSource {
  View<const LightView> lights;
  View<const ShadowLight> light_faces;
  View<const ShadowFace> faces;
  View<const float> depths;  // +inf where no caster
  int resolution;
  int pcf;            // kernel side in texels (1: a single nearest-texel test)
  double bias;        // world units subtracted from the point's depth ...
  double slope_bias;  // ... plus this many texel sizes at the point's depth (grazing surfaces)

  struct Cursor {
    uint32_t flags = 0;
  };

  // Omni lights: the cube face whose axis is the major axis of p - light.
  DV_HD int face_of(const ShadowLight& sl, const LightView& l, const dvec3& p) const {
    if (sl.face_count == 1) return sl.first_face;
    const dvec3 d = p - l.position;
    const dvec3 a = glm::abs(d);
    const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    return sl.first_face + 2 * axis + (d[axis] < 0.0 ? 1 : 0);
  }

  DV_HD double transmittance(Cursor&, const dvec3& p, int light) const {
    const LightView& l = lights[light];
    if (l.type == LightType::spot) {
      const dvec3 d = p - l.position;
      const double len = glm::length(d);
      if (len > 0.0 && outside_spot_cone(l, d / len)) return 0.0;
    }
    const ShadowFace& f = faces[face_of(light_faces[light], l, p)];
    const dvec4 clip = world_to_clip_point(f.projection, p);
    if (clip.w <= 0.0 && !f.orthographic) return 1.0;
    const double u = (clip.x / clip.w * 0.5 + 0.5) * resolution - 0.5;  // texel-centre coordinates
    const double v = (0.5 - clip.y / clip.w * 0.5) * resolution - 0.5;
    const double own = shadow_depth(f, p);
    const double texel = f.orthographic ? f.texel_size : own * f.texel_size;
    const double depth = own - bias - slope_bias * texel * 0.5 * double(pcf + 1);
    const int x0 = int(floor(u - 0.5 * (pcf - 1) + 0.5)),
              y0 = int(floor(v - 0.5 * (pcf - 1) + 0.5));
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
};

}  // namespace dv
