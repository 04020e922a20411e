// The DSM storage registry: every storage strategy registers here, once, on first use.
#include "strategies/storage/dsm_storage.h"

namespace dv {

void register_compact_storage(Registry<DsmStorage>& registry);
void register_texture3d_storage(Registry<DsmStorage>& registry);
void register_chunked_storage(Registry<DsmStorage>& registry);
void register_blocked_storage(Registry<DsmStorage>& registry);
void register_beer_storage(Registry<DsmStorage>& registry);
void register_avsm_storage(Registry<DsmStorage>& registry);
void register_moments_storage(Registry<DsmStorage>& registry);
void register_fourier_storage(Registry<DsmStorage>& registry);
void register_occupancy_storage(Registry<DsmStorage>& registry);

Registry<DsmStorage>& storage_registry() {
  static Registry<DsmStorage> registry = make_registry<DsmStorage>(
      "storage", {register_compact_storage, register_texture3d_storage, register_chunked_storage,
                  register_blocked_storage, register_beer_storage, register_avsm_storage,
                  register_moments_storage, register_fourier_storage, register_occupancy_storage});
  return registry;
}

}  // namespace dv
