// The storage and voxelizer registries. Their strategies register here as they are written;
// until then the families are empty and `deepvox list` says so.
#include "strategies/storage/dsm_storage.h"
#include "strategies/voxelizer/voxelizer.h"

namespace dv {

Registry<DsmStorage>& storage_registry() {
  static Registry<DsmStorage> registry("storage");
  return registry;
}

Registry<Voxelizer>& voxelizer_registry() {
  static Registry<Voxelizer> registry = [] {
    Registry<Voxelizer> r("voxelizer");
    register_exact_voxelizer(r);
    register_sat_voxelizer(r);
    return r;
  }();
  return registry;
}

}  // namespace dv
