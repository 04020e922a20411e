// The shadow-method registry: every method registers here, once, on first use, and its traits
// (core/strategy_traits.h: plot family and marker; dsm is plotted as its storage) stand beside
// the registration list.
#include <map>

#include "core/strategy_traits.h"
#include "strategies/shadow/shadow_method.h"

namespace dv {

void register_no_shadows(Registry<ShadowMethod>& registry);
void register_reference_shadows(Registry<ShadowMethod>& registry);
void register_shadow_maps(Registry<ShadowMethod>& registry);
void register_dsm_shadows(Registry<ShadowMethod>& registry);
void register_transmittance_slicemap(Registry<ShadowMethod>& registry);
void register_auto_shadows(Registry<ShadowMethod>& registry);

Registry<ShadowMethod>& shadow_registry() {
  static Registry<ShadowMethod> registry = make_registry<ShadowMethod>(
      "shadow method",
      {register_no_shadows, register_reference_shadows, register_shadow_maps, register_dsm_shadows,
       register_transmittance_slicemap, register_auto_shadows});
  return registry;
}

const StrategyTraits* shadow_traits(const std::string& name) {
  static const std::map<std::string, StrategyTraits> traits{
      {"none", {"no shadows", "#999999", "X"}},
      {"reference", {"exact oracle", "black", "*"}},
      {"shadowmap", {"shadow maps", "#1f77b4", "o"}},
      {"dsm", {"DSM, node lists", "#ff7f0e", "o", "storage"}},
      {"transmittance-slicemap", {"slice maps", "#2ca02c", "o"}},
      {"auto", {"effect planner", "#9467bd", "P"}}};
  auto it = traits.find(lowercase(name));
  return it == traits.end() ? nullptr : &it->second;
}

}  // namespace dv
