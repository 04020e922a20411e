// Kernel side of the `dsm` shadow method: the transmittance of a light at a point from that
// light's deep shadow maps. The point's face and texel-centre coordinates come from the shared
// light-face helpers (light_faces.h), its depth (distance from the light, or from an
// orthographic map's near plane) less the receiver bias against self-shadowing (receiver_depth:
// for a surface point a constant plus `slope_bias` texel sizes times its tangent to the light,
// over the filter's reach; none for points in media and volume samples). Unfiltered: the nearest
// texel's V'(z). Bilinear (Knecht eq. 4.18/4.19): the four texels around the point, V' of each
// weighted bilinearly, so attenuation is filtered, not optical depth. Texels outside the map count
// as lit; points outside a spot cone get nothing. The per-ray cursor keeps each (light, tap)'s last
// node index for the coherent search.
// Clustered lights (ShadowLight::clustered) multiply the visibilities of their cluster faces.
// Colour: with the colour side channel (engine/dsm/dsm_colour.h; only for scenes with tinted
// casters) each tap's V' becomes per-channel transmittances (V'^k_c, grey-scaled behind the
// texel's last tint) before the filter; without it the answer is grey.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/hd.h"
#include "cuda/buffer.h"
#include "engine/dsm/dsm_colour.h"
#include "engine/raster/light_faces.h"
#include "engine/raster/shadow_receiver.h"
#include "engine/scene/surface_transmittance.h"
#include "strategies/storage/dsm_reader.h"

namespace dv {

inline constexpr int kDsmCursorLights = 8;  // lights with coherent-search state per ray

struct DsmSource {
  View<const LightView> lights;
  View<const ShadowLight> light_faces;
  View<const ShadowFace> faces;
  DsmReader reader;
  int resolution;
  double bias;
  double slope_bias;
  bool bilinear;
  View<const DsmColourTexel> colour_texels{};  // per texel (dsm_colour.h); empty: grey maps

  struct Cursor {
    uint32_t flags = 0;
    int hint[kDsmCursorLights * 4];  // per (light, tap): node index, -1 for none yet
    DV_HD Cursor() {
      for (int& h : hint) h = -1;
    }
  };

  // Texel (x, y) of face f, -1 outside the map.
  DV_HD int64_t texel_index(const ShadowFace& f, int x, int y) const {
    if (x < 0 || y < 0 || x >= resolution || y >= resolution) return -1;
    return f.offset + int64_t(y) * resolution + x;
  }

  // V'(z) of texel (x, y) of face f (1 outside the map) read alone, through the reader's
  // single-texel visibility: the reference the tests hold a lookup's taps read together to.
  DV_HD float texel_visibility(const ShadowFace& f, int x, int y, float z, int& hint) const {
    const int64_t t = texel_index(f, x, y);
    return t < 0 ? 1.0f : reader.visibility(t, z, hint);
  }

  DV_HD double transmittance(Cursor& cursor, const ShadowReceiver& r, int light) const {
    return luminance(transmittance_rgb(cursor, r, light));
  }

  DV_HD dvec3 transmittance_rgb(Cursor& cursor, const ShadowReceiver& r, int light) const {
    int scratch[4] = {-1, -1, -1, -1};
    return hinted_transmittance(r, light,
                                light < kDsmCursorLights ? cursor.hint + 4 * light : scratch);
  }

  // transmittance() with the caller's four coherent-search slots for this light (the planner's
  // per-light sources keep them in their own cursor, planned_shadow_device.h).
  DV_HD dvec3 hinted_transmittance(const ShadowReceiver& r, int light, int* hint) const {
    const dvec3& p = r.point;
    const LightView& l = lights[light];
    if (outside_light_cone(l, p)) return dvec3(0.0);
    if (light_faces[light].clustered) return clustered_transmittance(light_faces[light], r);
    const ShadowFace& f = faces[face_of(light_faces[light], l, p)];
    FacePoint fp;
    if (!project_to_face(f, resolution, p, fp)) return dvec3(1.0);
    return face_visibility_rgb(f, fp, r, hint);
  }

  // Knecht eq. 3.12: the product of the visibilities of the light's cluster faces whose window
  // holds the point (each holds only its cluster's objects); a face that misses it counts 1.
  // No coherent search across clusters (each face starts its search afresh).
  DV_HD dvec3 clustered_transmittance(const ShadowLight& sl, const ShadowReceiver& r) const {
    const dvec3& p = r.point;
    dvec3 t(1.0);
    for (int i = 0; i < sl.face_count; ++i) {
      const ShadowFace& f = faces[sl.first_face + i];
      FacePoint fp;
      if (!project_to_face(f, resolution, p, fp)) continue;
      if (!(fp.u >= -0.5 && fp.u < resolution - 0.5 && fp.v >= -0.5 && fp.v < resolution - 0.5))
        continue;
      int hint[4] = {-1, -1, -1, -1};
      t *= face_visibility_rgb(f, fp, r, hint);
    }
    return t;
  }

  // V' of face f at the point fp of receiver r, nearest or bilinear; hint: 4 coherent-search
  // slots.
  DV_HD double face_visibility(const ShadowFace& f, const FacePoint& fp, const ShadowReceiver& r,
                               int* hint) const {
    return luminance(face_visibility_rgb(f, fp, r, hint));
  }

  // face_visibility per colour channel.
  DV_HD dvec3 face_visibility_rgb(const ShadowFace& f, const FacePoint& fp, const ShadowReceiver& r,
                                  int* hint) const {
    const float z = float(receiver_depth(f, r, fp.depth, bias, slope_bias, bilinear ? 1.0 : 0.5));
    // A point beyond the face's texels is lit. One on them is looked up with its coordinates
    // clamped to the texel centres (clamp to edge): a point on the face's outer edge (an omni
    // seam, where face_of's tie picks this face) would otherwise round to the texel beyond it,
    // and in the outer half of a border texel the bilinear filter would blend in that texel's
    // lit value 1: light leaking along every omni seam and at the spot cone's edge. The edge
    // takes 1e-6 texels of slack for the projection's rounding of points on a seam.
    const double lo = -0.5 - 1e-6, hi = resolution - 0.5 + 1e-6;
    if (!(fp.u >= lo && fp.u <= hi && fp.v >= lo && fp.v <= hi)) return dvec3(1.0);
    const double u = clamp_value(fp.u, 0.0, resolution - 1.0);
    const double v = clamp_value(fp.v, 0.0, resolution - 1.0);
    DsmTaps taps;
    double wx = 0.0, wy = 0.0;
    if (bilinear) {
      const double fx = floor(u), fy = floor(v);
      const int x = int(fx), y = int(fy);
      wx = u - fx;
      wy = v - fy;
      taps.texel[0] = texel_index(f, x, y);
      taps.texel[1] = texel_index(f, x + 1, y);
      taps.texel[2] = texel_index(f, x, y + 1);
      taps.texel[3] = texel_index(f, x + 1, y + 1);
      taps.count = 4;
    } else {
      taps.texel[0] = texel_index(f, int(floor(u + 0.5)), int(floor(v + 0.5)));
      taps.count = 1;
    }
    float tv[4];
    reader.visibilities(taps, z, hint, tv);
    if (colour_texels.empty()) {
      if (!bilinear) return dvec3(tv[0]);
      const double v00 = tv[0], v10 = tv[1], v01 = tv[2], v11 = tv[3];
      return dvec3((1.0 - wy) * ((1.0 - wx) * v00 + wx * v10) + wy * ((1.0 - wx) * v01 + wx * v11));
    }
    dvec3 c[4];
    for (int i = 0; i < taps.count; ++i)
      c[i] = taps.texel[i] < 0 ? dvec3(1.0)
                               : coloured_visibility(tv[i], z, colour_texels[taps.texel[i]]);
    if (!bilinear) return c[0];
    return (1.0 - wy) * ((1.0 - wx) * c[0] + wx * c[1]) + wy * ((1.0 - wx) * c[2] + wx * c[3]);
  }
};

}  // namespace dv
