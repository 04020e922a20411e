// The effects table behind `--explain` (see effect_losses.h). Each row says how an object shows
// the effect (from Material::alpha, transmission, colour and base texture, Interior's kind and
// sigma_tint) and, per shadow method, what its shadows keep, approximate or drop. Shadows are RGB
// (docs/rendering.md): the oracle exactly, dsm through its colour side channel
// (engine/dsm/dsm_colour.h), shadowmap and transmittance-slicemap through the glass layer of
// their depth maps (shadow_map_device.h), whose depth maps cast a fragment when its opacity
// reaches kDepthMapOpaqueAlpha (depth_maps.h); media reach the maps by their boundaries
// (translucent_casters.h).
#include "strategies/shadow/effect_losses.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "strategies/shadow/depth_maps.h"

namespace dv {

namespace {

// The methods the table has a column for, in column order.
constexpr std::array<const char*, 6> kMethods = {
    "none", "shadowmap", "dsm", "transmittance-slicemap", "reference", "auto"};

// The rows' words for shadowmap and the slicemap's opaque map say 0.5.
static_assert(kDepthMapOpaqueAlpha == 0.5);
// The textured-glass row's words say 2/255.
static_assert(kGreyTexelTolerance == 2);

// Glass whose colour comes from its base-colour texture: the texture has coloured texels, so the
// colour channels switch on for it even under a grey factor.
bool glass_coloured_by_texture(const Scene& scene, const Object& o) {
  const Material& m = o.material;
  return m.transmission > 0.0 && o.interior.kind == InteriorKind::none && m.base_texture >= 0 &&
         texture_has_colour(scene.textures[size_t(m.base_texture)]);
}

struct EffectRow {
  const char* one;   // the effect, for one object
  const char* many;  // for several
  bool (*shows)(const Scene& scene, const Object& o);
  std::array<const char*, kMethods.size()> treatment;  // per kMethods entry
};

// To add an effect: one row here.
const EffectRow kEffects[] = {
    {"translucent caster (0 < alpha < 1)",
     "translucent casters (0 < alpha < 1)",
     [](const Scene&, const Object& o) {
       return o.material.alpha > 0.0 && o.material.alpha < 1.0 && o.material.transmission <= 0.0;
     },
     {"dropped (no shadows)",
      "thresholded: one depth layer, so alpha >= 0.5 casts a full shadow and alpha < 0.5 none",
      "kept: its alpha per crossing, in visibility functions compressed to within eps",
      "approximated: voxelized into the light's slices with one alpha, the mean over the "
      "translucent casters when theirs differ",
      "kept (exact)",
      "kept as dsm keeps it: the planner runs dsm for every light that reaches it"}},
    {"alpha-textured caster (MASK or BLEND)",
     "alpha-textured casters (MASK or BLEND)",
     [](const Scene&, const Object& o) {
       return o.material.base_texture >= 0 && o.material.alpha_mode != AlphaMode::opaque;
     },
     {"dropped (no shadows)",
      "MASK cut per shadow-map texel; BLEND thresholded per texel: a full shadow where the "
      "texel's alpha times the factor's reaches 0.5, none below",
      "kept: MASK cut and BLEND alpha per crossing of each texel's ray, in visibility functions "
      "compressed to within eps",
      "MASK cut per texel by the opaque depth map; BLEND approximated: voxelized with the "
      "factor's alpha everywhere, since the grid holds no texture (with a factor's alpha of 1 "
      "only its fully opaque texels cast, through the opaque depth map)",
      "kept (exact: the texel's coverage at every crossing)",
      "MASK on an opaque object cut per texel by the shadowmap the planner runs where every "
      "caster is opaque (else by dsm); BLEND kept as dsm keeps it: the planner runs dsm for "
      "every light that reaches it"}},
    {"transmissive (glass) caster",
     "transmissive (glass) casters",
     [](const Scene&, const Object& o) { return o.material.transmission > 0.0; },
     {"dropped (no shadows)",
      "approximated: a glass layer, one per texel: the crossing rule (Fresnel at the texel "
      "ray's angle, tint) multiplied over the texel's glass crossings, applied beyond the "
      "nearest, so a receiver between two of them gets both (no refraction, no caustics)",
      "kept: each crossing's opacity, 1 - the luminance of the crossing rule (Fresnel at the "
      "texel ray's angle), in visibility functions compressed to within eps; its colour by the "
      "colour side channel (no refraction, no caustics)",
      "approximated as shadowmap does: the opaque depth map's glass layer, one per texel (no "
      "refraction, no caustics)",
      "kept (exact: the crossing rule with Fresnel at every crossing; thin-walled, no "
      "refraction, no caustics)",
      "kept as dsm keeps it: the planner runs dsm for every light that reaches it"}},
    {"constant medium",
     "constant media",
     [](const Scene&, const Object& o) { return o.interior.kind == InteriorKind::constant; },
     {"dropped (no shadows)",
      "thresholded at its boundary: a full shadow where the medium's opacity across the "
      "object's thinnest extent d, 1 - exp(-sigma d), or its surface alpha reaches 0.5, else "
      "none (inside glass: the glass layer's Fresnel alone)",
      "kept: its extinction along each chord, in the compressed visibility functions",
      "approximated: its boundary is voxelized, each crossing 1 - exp(-sigma d / 2) with d the "
      "object's thinnest extent, under the translucent casters' one alpha (their mean when they "
      "differ)",
      "kept (exact chord lengths)",
      "kept as dsm keeps it: the planner runs dsm for every light that reaches it"}},
    {"volume",
     "volumes",
     [](const Scene&, const Object& o) { return o.interior.kind == InteriorKind::volume; },
     {"dropped (no shadows)",
      "thresholded at its boundary: a full shadow where 1 - exp(-sigma_max d), sigma_max its "
      "transfer function's largest extinction and d the object's thinnest extent, reaches 0.5, "
      "else none",
      "approximated: sampled at the volume step when the maps are generated",
      "approximated: its boundary is voxelized, each crossing 1 - exp(-sigma_max d / 2) with "
      "sigma_max its transfer function's largest extinction and d the object's thinnest extent, "
      "under the translucent casters' one alpha (their mean when they differ)",
      "kept (closed form per cell, exact up to rounding)",
      "approximated as dsm does: the planner runs dsm with volume sampling for every light "
      "that reaches it"}},
    {"tinted medium or coloured glass",
     "tinted media or coloured glass objects",
     object_tints_light,
     {"dropped (no shadows)",
      "coloured glass kept in the glass layer (one colour filter per texel); a tinted medium's "
      "colour dropped: its boundary casts grey",
      "kept by the colour side channel: exact for one tint per texel at every depth; where "
      "differently tinted casters share a texel, the far end's mix holds at every depth",
      "coloured glass kept in the opaque depth map's glass layer (one colour filter per texel); "
      "a tinted medium's colour dropped: its boundary is voxelized grey",
      "kept (exact, per colour channel)",
      "kept as dsm keeps it (the colour side channel): the planner runs dsm for every light "
      "that reaches it"}},
    {"glass coloured by its base-colour texture",
     "glass objects coloured by their base-colour textures",
     glass_coloured_by_texture,
     {"dropped (no shadows)",
      "kept in the glass layer: the crossing rule takes the texture's colour where each texel's "
      "ray crosses the glass (one colour filter per texel)",
      "colour side channel on, because the texture has coloured texels (R, G, B differing by "
      "more than 2/255) even where the factor is grey: its pass samples the texture's colour "
      "where each texel's ray crosses the glass",
      "kept in the opaque depth map's glass layer, the texture's colour where each texel's ray "
      "crosses the glass (one colour filter per texel)",
      "kept (exact: the texel's colour at every crossing)",
      "kept as dsm keeps it (the colour side channel, on for the texture's colour): the planner "
      "runs dsm for every light that reaches it"}},
};

}  // namespace

std::vector<EffectTreatment> effect_treatments(const Scene& scene, const std::string& method) {
  const auto column = std::find(kMethods.begin(), kMethods.end(), method);
  std::vector<EffectTreatment> out;
  for (const EffectRow& row : kEffects) {
    const int n = int(std::count_if(scene.objects.begin(), scene.objects.end(),
                                    [&](const Object& o) { return row.shows(scene, o); }));
    if (n == 0) continue;
    out.push_back({n == 1 ? row.one : row.many, n,
                   column == kMethods.end() ? "not described for this method"
                                            : row.treatment[size_t(column - kMethods.begin())]});
  }
  return out;
}

std::string explain_effects(const Scene& scene, const std::string& method) {
  const std::vector<EffectTreatment> effects = effect_treatments(scene, method);
  if (effects.empty())
    return "effects: every shadow caster is opaque; " + method + " drops nothing\n";
  std::string out = "effects in the scene and what " + method + " shadows do with them:\n";
  for (const EffectTreatment& e : effects)
    out += "  " + std::to_string(e.objects) + " " + e.effect + ": " + e.treatment + "\n";
  return out;
}

}  // namespace dv
