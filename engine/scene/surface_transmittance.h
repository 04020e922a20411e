// What one crossing of a surface lets through, per colour channel: the one rule the exact oracle,
// the camera pass and every shadow method share (docs/rendering.md, "The exact oracle").
//
//   T = (1 - a) + a t (1 - F(cos)) c        per channel
//
// a the surface's coverage (alpha + transmission of the material: what its alphaMode leaves of
// the surface), t the share of the covered part that is glass (transmission / a), c the base
// colour for a thin-walled surface or white when the object has an interior (KHR_materials_volume:
// the medium inside tints, the surfaces only add Fresnel), F Schlick's Fresnel reflectance
// F0 + (1 - F0)(1 - |cos|)^5 with F0 = ((ior - 1) / (ior + 1))^2 and cos the cosine between the
// ray and the surface's normal. A surface without transmission keeps T = 1 - alpha exactly, so
// grey scenes are unchanged. `coverage` and `base_color` are per-hit inputs (textures may vary
// them); call sites without textures pass the material's constants (material_coverage, o.color).
// Host and device code.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/hd.h"
#include "core/math.h"
#include "engine/scene/scene_view.h"
#include "engine/scene/texture_sampling.h"

namespace dv {

// Rec. 709 luminance weights: how RGB transmittance becomes the one number scalar consumers
// (probe's light0 column, the DSM storages, error metrics) read.
inline constexpr double kLuminanceR = 0.2126, kLuminanceG = 0.7152, kLuminanceB = 0.0722;

// Luminance of an RGB transmittance; a grey value is returned unchanged (bit for bit).
DV_HD inline double luminance(const dvec3& c) {
  if (c.x == c.y && c.y == c.z) return c.x;
  return kLuminanceR * c.x + kLuminanceG * c.y + kLuminanceB * c.z;
}

// Schlick's approximation of the Fresnel reflectance of a dielectric of index `ior` in air.
DV_HD inline double fresnel_schlick(double ior, double cos_to_normal) {
  const double r = (ior - 1.0) / (ior + 1.0);
  const double f0 = r * r;
  const double m = 1.0 - min_value(cos_to_normal < 0.0 ? -cos_to_normal : cos_to_normal, 1.0);
  const double m2 = m * m;
  return f0 + (1.0 - f0) * m2 * m2 * m;
}

// The material's own coverage (no texture): what the surface covers, opaque or glass.
DV_HD inline double material_coverage(const ObjectView& o) {
  return o.alpha + o.transmission;
}

// Whether crossings of this object can tint (any channel differs): glass with a coloured base
// (its factor, or a base-colour texture with colour) on a thin-walled object, or a tinted
// constant medium inside. object_tints_light (engine/scene/scene.h) is the same on the host's
// Scene.
DV_HD inline bool tints_light(const ObjectView& o) {
  const bool coloured_base =
      !(o.color.x == o.color.y && o.color.y == o.color.z) || (o.texture >= 0 && o.texture_colour);
  const bool glass_tint = o.transmission > 0.0 && o.interior == InteriorKind::none && coloured_base;
  const dvec3& s = o.sigma_rgb;
  const bool medium_tint = o.interior == InteriorKind::constant && !(s.x == s.y && s.y == s.z);
  return glass_tint || medium_tint;
}

// The crossing rule (see above) for a ray meeting the surface at `cos_to_normal`.
DV_HD inline dvec3 surface_transmittance(const ObjectView& o, double cos_to_normal, double coverage,
                                         const dvec3& base_color) {
  if (o.transmission <= 0.0) return dvec3(1.0 - coverage);
  const double glass_share = min_value(o.transmission / material_coverage(o), 1.0);
  const dvec3 tint = o.interior == InteriorKind::none ? base_color : dvec3(1.0);
  const double through = coverage * glass_share * (1.0 - fresnel_schlick(o.ior, cos_to_normal));
  return dvec3(1.0 - coverage) + through * tint;
}

// The coverage (opaque plus glass part) of `o` at point p of `triangle`: the material's, or its
// texture's there.
DV_HD inline double hit_coverage(const SceneView& s, const ObjectView& o, uint32_t triangle,
                                 const dvec3& p) {
  if (o.texture < 0) return material_coverage(o);
  const SurfaceLook look = surface_look(s, o, triangle, p);
  return look.alpha + look.transmission;
}

// Unit geometric normal of a triangle (zero for a degenerate one).
DV_HD inline dvec3 triangle_normal(const SceneView& s, uint32_t triangle) {
  const u32vec3 tri = s.triangles[triangle];
  const dvec3 p0 = s.vertices[tri.x];
  const dvec3 n = glm::cross(s.vertices[tri.y] - p0, s.vertices[tri.z] - p0);
  const double len = glm::length(n);
  return len > 0.0 ? n / len : dvec3(0.0);
}

// The crossing rule for a ray of unit direction `dir` through `triangle` of `o` at point p: the
// material's constants, or where a base-colour texture decides them, the coverage and colour
// of its texel at p (engine/scene/texture_sampling.h). The normal is computed only for
// transmissive surfaces.
DV_HD inline dvec3 crossing_transmittance(const SceneView& s, const ObjectView& o,
                                          uint32_t triangle, const dvec3& dir, const dvec3& p) {
  const double cos_to_normal =
      o.transmission > 0.0 ? glm::dot(triangle_normal(s, triangle), dir) : 1.0;
  if (o.texture < 0) return surface_transmittance(o, cos_to_normal, material_coverage(o), o.color);
  const SurfaceLook look = surface_look(s, o, triangle, p);
  return surface_transmittance(o, cos_to_normal, look.alpha + look.transmission, look.color);
}

// The light one crossing removes, as the scalar opacity the storages and maps carry: 1 minus
// the crossing's luminance transmittance (the surface's alpha at p for a surface without
// transmission).
DV_HD inline double crossing_opacity(const SceneView& s, const ObjectView& o, uint32_t triangle,
                                     const dvec3& dir, const dvec3& p) {
  if (o.transmission <= 0.0) return surface_alpha(s, triangle, p);
  return 1.0 - luminance(crossing_transmittance(s, o, triangle, dir, p));
}

}  // namespace dv
