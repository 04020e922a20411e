// The effects table behind `--explain` (see effect_losses.h). Each row says how an object shows
// the effect (from Material::alpha and transmission, Interior's kind and sigma_tint) and, per
// shadow method, what its shadows keep, approximate or drop. Shadows are scalar everywhere
// (engine/oracle/transmittance.h): colour is the camera pass's alone.
#include "strategies/shadow/effect_losses.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace dv {

namespace {

// The methods the table has a column for, in column order.
constexpr std::array<const char*, 6> kMethods = {
    "none", "shadowmap", "dsm", "transmittance-slicemap", "reference", "auto"};

bool grey(const dvec3& c) {
  return std::abs(c.x - c.y) < 1e-9 && std::abs(c.y - c.z) < 1e-9;
}

struct EffectRow {
  const char* one;   // the effect, for one object
  const char* many;  // for several
  bool (*shows)(const Object& o);
  std::array<const char*, kMethods.size()> treatment;  // per kMethods entry
};

// To add an effect (alpha-textured casters, coloured glass shadows, ...): one row here.
const EffectRow kEffects[] = {
    {"translucent caster (0 < alpha < 1)",
     "translucent casters (0 < alpha < 1)",
     [](const Object& o) {
       return o.material.alpha > 0.0 && o.material.alpha < 1.0 && o.material.transmission <= 0.0;
     },
     {"dropped (no shadows)", "opaque: one depth layer, so any alpha > 0 casts a full shadow",
      "kept: its alpha per crossing, in visibility functions compressed to within eps",
      "approximated: voxelized into the light's slices with one alpha, the mean over the "
      "translucent objects when theirs differ",
      "kept (exact)",
      "kept as dsm keeps it: the planner runs dsm for every light that reaches it"}},
    {"transmissive (glass) caster",
     "transmissive (glass) casters",
     [](const Object& o) { return o.material.transmission > 0.0; },
     {"dropped (no shadows)",
      "opaque unless fully transmissive (then no shadow at all): alpha = 1 - transmission "
      "is one depth layer",
      "approximated: a thin surface of alpha 1 - transmission per crossing (no refraction, no "
      "caustics)",
      "approximated: a thin surface of alpha 1 - transmission, voxelized with the translucent "
      "casters' mean alpha",
      "approximated: a thin surface of alpha 1 - transmission per crossing (no refraction, no "
      "caustics)",
      "as dsm: the planner runs dsm for every light that reaches it"}},
    {"constant medium",
     "constant media",
     [](const Object& o) { return o.interior.kind == InteriorKind::constant; },
     {"dropped (no shadows)", "dropped: only its boundary casts, opaque when its alpha > 0",
      "kept: its extinction along each chord, in the compressed visibility functions",
      "dropped: only surfaces are voxelized (its boundary, when 0 < alpha < 1)",
      "kept (exact chord lengths)",
      "kept as dsm keeps it: the planner runs dsm for every light that reaches it"}},
    {"volume",
     "volumes",
     [](const Object& o) { return o.interior.kind == InteriorKind::volume; },
     {"dropped (no shadows)", "dropped: only its boundary casts, opaque when its alpha > 0",
      "approximated: sampled at the volume step when the maps are generated",
      "dropped: only surfaces are voxelized", "kept (adaptive Simpson to 1e-9)",
      "approximated as dsm does: the planner runs dsm with volume sampling for every light "
      "that reaches it"}},
    {"tinted medium or coloured glass",
     "tinted media or coloured glass objects",
     [](const Object& o) {
       return (o.interior.kind == InteriorKind::constant && !grey(o.interior.sigma_tint)) ||
              (o.material.transmission > 0.0 && !grey(o.material.color));
     },
     {"dropped (no shadows)", "colour dropped: shadows are grey",
      "colour dropped: shadows are grey (the mean of the three extinctions; glass untinted)",
      "colour dropped: shadows are grey",
      "colour dropped: the oracle is scalar (the mean of the three extinctions; glass "
      "untinted); only the camera's view through it is tinted",
      "colour dropped: shadows are grey"}},
};

}  // namespace

std::vector<EffectTreatment> effect_treatments(const Scene& scene, const std::string& method) {
  const auto column = std::find(kMethods.begin(), kMethods.end(), method);
  std::vector<EffectTreatment> out;
  for (const EffectRow& row : kEffects) {
    const int n = int(std::count_if(scene.objects.begin(), scene.objects.end(), row.shows));
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
