// OpenVDB volumes without OpenVDB: the lean GPU-node build, or DEEPVOX_OPENVDB=OFF. The linker
// takes this file only when nothing in the program defines the functions of vdb_io.h
// (render/io/CMakeLists.txt), so it must define exactly the functions vdb_openvdb.cpp does.
#include "core/error.h"
#include "render/io/vdb_io.h"

namespace dv {

bool vdb_supported() {
  return false;
}

void require_vdb_support(const std::string& path) {
  throw InputError(
      path,
      "this deepvox is built without OpenVDB (the lean build, or DEEPVOX_OPENVDB=OFF), "
      "so it cannot read or write .vdb files; use the full build, or a raw volume");
}

VolumeGrid load_vdb_volume(const std::string& path, const std::string&) {
  require_vdb_support(path);
  return {};
}

void write_vdb_occupancy(const std::string& path, const VoxelGrid&) {
  require_vdb_support(path);
}

}  // namespace dv
