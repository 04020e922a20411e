// The deep shadow maps' colour side channel. Every storage carries one visibility function per
// texel: the luminance-weighted opacity of glass crossings and the scalar extinction sigma of
// media (what grey scenes store). For scenes where some caster tints light (coloured glass,
// tinted media: tints_light in engine/scene/surface_transmittance.h) a second pass walks each
// texel's centre ray once more and keeps, per texel, the per-channel exponents
//   k_c = (optical depth of channel c) / (optical depth of the stored function)
// summed up to the first opaque crossing; a lookup turns V' into T_c = V'^k_c. This is exact
// for one tint per texel (one glass pane, one tinted medium, or several of the same colour) at
// every depth, and approximate where differently tinted casters share a texel (the far end's
// mix then holds for every depth). It costs 12 bytes per texel, only for scenes with tinted
// casters; grey scenes get no pass and no bytes. Host and device code (the lookup) and the
// pass (dsm_colour.cpp, compiled by nvcc when CUDA is on).
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

// k per texel of `generator`'s faces into `exponents` (texel_count entries); texels whose ray
// stays clear get (1, 1, 1).
void generate_colour_exponents(Backend backend, const DsmGenerator& generator,
                               View<vec3> exponents);

// The per-channel transmittance of a texel whose stored visibility is v.
DV_HD inline dvec3 coloured_visibility(double v, const vec3& k) {
  if (v <= 0.0) return dvec3(0.0);
  return dvec3(pow(v, double(k.x)), pow(v, double(k.y)), pow(v, double(k.z)));
}

}  // namespace dv
