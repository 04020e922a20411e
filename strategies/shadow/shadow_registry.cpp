// The shadow-method registry: every method registers here, once, on first use.
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

}  // namespace dv
