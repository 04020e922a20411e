// Kernel side of the conventional depth shadow map (Williams 1978; Brabec 2003 ch. 4-5): per
// light one face (spot: perspective over the cone; directional: orthographic fitted to the
// casters) or six 90-degree faces (omni), each a square map of the nearest caster's depth.
// A point is lit where its own depth, less the receiver bias, does not exceed the stored depth
// (light_faces.h, receiver_depth: for surface points a constant plus `slope_bias` texel sizes
// times the receiver's tangent to the light, over the PCF kernel's reach; none elsewhere); PCF
// averages that test over pcf x pcf texels around the point's projection (Reeves et al.:
// compare, then filter). Every surface whose caster opacity reaches kDepthMapOpaqueAlpha
// (depth_maps.h: its alpha at that point, or an interior medium's opacity across the object)
// casts a full shadow, the others none: this is the opaque-shadow baseline. Host and device code.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "cuda/buffer.h"
#include "engine/raster/light_faces.h"
#include "engine/raster/shadow_receiver.h"
#include "engine/scene/scene_view.h"

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

  struct Cursor {
    uint32_t flags = 0;
  };

  DV_HD double transmittance(Cursor&, const ShadowReceiver& r, int light) const {
    const dvec3& p = r.point;
    const LightView& l = lights[light];
    if (outside_light_cone(l, p)) return 0.0;
    const ShadowFace& f = faces[face_of(light_faces[light], l, p)];
    FacePoint fp;
    if (!project_to_face(f, resolution, p, fp)) return 1.0;
    const double depth = receiver_depth(f, r, fp.depth, bias, slope_bias, 0.5 * double(pcf + 1));
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
};

}  // namespace dv
