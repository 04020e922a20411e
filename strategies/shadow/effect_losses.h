// What each shadow method drops or approximates of the effects a scene holds (`--explain`): the
// effects are found from the objects' materials and interiors, and what a method does with each
// comes from one table in effect_losses.cpp (one row per effect, one entry per method), so a new
// effect is one row and a new method one column.
#pragma once

#include <string>
#include <vector>

#include "engine/scene/scene.h"

namespace dv {

// One effect the scene holds: how many objects show it and what `method` does with it.
struct EffectTreatment {
  std::string effect;     // plain words, singular or plural by the count
  int objects = 0;        // how many objects show it (> 0)
  std::string treatment;  // what the method does with it, e.g. "kept (exact)"
};

// The effects present in `scene` (in table order), each with what shadow method `method` (a
// registered name, `auto` included) does with it. Empty when every caster is opaque.
std::vector<EffectTreatment> effect_treatments(const Scene& scene, const std::string& method);

// effect_treatments in plain words, a header line and one line per effect: what `--explain`
// prints.
std::string explain_effects(const Scene& scene, const std::string& method);

}  // namespace dv
