// The deep shadow maps' colour side channel. Every storage carries one visibility function per
// texel: the luminance-weighted opacity of glass crossings and the scalar extinction sigma of
// media (what grey scenes store). For scenes where some caster tints light (coloured glass,
// tinted media: tints_light in engine/scene/surface_transmittance.h) a second pass walks each
// texel's centre ray once more and keeps, per texel, where the last tinted stretch (a coloured
// crossing or a tinted constant medium) ends, z_t, the optical depth tau_t of the stored
// function there and the per-channel exponents
//   k_c = (optical depth of channel c) / (optical depth of the stored function), both to z_t.
// A lookup of V' at depth z turns it into T_c = V'^k_c up to z_t and beyond it into
// T_c = exp(-tau_t k_c) min(1, V' exp(tau_t)): the layers behind the last tint are grey, so they
// scale every channel by the ratio V'(z) / V'(z_t) (with V'(z_t) from the walk, no second
// lookup). This is exact for one tint per texel (one glass pane, one tinted medium, or several
// of the same colour) at every depth, grey translucent layers behind it included, and
// approximate where differently tinted casters share a texel (their mix at z_t then holds at
// every depth in front of it). It costs 20 bytes per texel, only for scenes with tinted casters;
// grey scenes get no pass and no bytes. Host and device code (the lookup) and the pass
// (dsm_colour.cpp, compiled by nvcc when CUDA is on).
#pragma once

#include <cmath>

#include "core/hd.h"
#include "core/math.h"
#include "cuda/buffer.h"
#include "cuda/execute.h"
#include "engine/dsm/dsm_generator.h"
#include "engine/scene/scene_view.h"

namespace dv {

// Whether any object of the scene can tint light, so that maps of it carry the side channel.
bool scene_tints_light(const SceneData& scene);

// One texel's side channel. A texel whose ray meets no tint keeps k = 1 and z_t = +inf: its
// channels are V' each.
struct DsmColourTexel {
  vec3 k{1.0f};                      // per-channel exponents up to tinted_end
  float tinted_end = 3.0e38f;        // z_t: depth where the last tinted stretch ends
  float tinted_optical_depth = 0.f;  // tau_t: optical depth of the stored function at z_t
};

// The side channel of every texel of `generator`'s faces into `texels` (texel_count entries).
void generate_colour_texels(Backend backend, const DsmGenerator& generator,
                            View<DsmColourTexel> texels);

// The per-channel transmittance at depth z of a texel whose stored visibility there is v.
DV_HD inline dvec3 coloured_visibility(double v, double z, const DsmColourTexel& c) {
  if (v <= 0.0) return dvec3(0.0);
  const dvec3 k(c.k);
  if (z <= double(c.tinted_end)) return dvec3(pow(v, k.x), pow(v, k.y), pow(v, k.z));
  const double tau = c.tinted_optical_depth;
  const double grey = min_value(1.0, v * exp(tau));
  return dvec3(exp(-tau * k.x), exp(-tau * k.y), exp(-tau * k.z)) * grey;
}

}  // namespace dv
