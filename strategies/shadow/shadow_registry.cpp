// The shadow-method registry: every method registers here, once, on first use.
#include "strategies/shadow/shadow_method.h"

namespace dv {

Registry<ShadowMethod>& shadow_registry() {
  static Registry<ShadowMethod> registry = [] {
    Registry<ShadowMethod> r("shadow method");
    register_no_shadows(r);
    register_reference_shadows(r);
    register_shadow_maps(r);
    register_dsm_shadows(r);
    register_transmittance_slicemap(r);
    register_auto_shadows(r);
    return r;
  }();
  return registry;
}

}  // namespace dv
