// The storage and voxelizer registries: every strategy of the two families registers here.
#include "strategies/storage/dsm_storage.h"
#include "strategies/voxelizer/voxelizer.h"

namespace dv {

Registry<DsmStorage>& storage_registry() {
  static Registry<DsmStorage> registry = [] {
    Registry<DsmStorage> r("storage");
    register_compact_storage(r);
    register_texture3d_storage(r);
    register_chunked_storage(r);
    register_blocked_storage(r);
    register_moments_storage(r);
    register_fourier_storage(r);
    return r;
  }();
  return registry;
}

Registry<Voxelizer>& voxelizer_registry() {
  static Registry<Voxelizer> registry = [] {
    Registry<Voxelizer> r("voxelizer");
    register_exact_voxelizer(r);
    register_sat_voxelizer(r);
    register_slicemap_voxelizer(r);
    register_atlas_voxelizers(r);
    return r;
  }();
  return registry;
}

}  // namespace dv
