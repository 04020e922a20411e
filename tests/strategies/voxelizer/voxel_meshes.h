// Inputs the voxel tests share: triangle soups from corner lists, and the meshes (icosphere,
// torus, the bunny scan, the 11,858-triangle quad) every voxelizer is checked on.
#pragma once

#include <vector>

#include "experiments/source_paths.h"
#include "render/load/mesh_generators.h"
#include "strategies/voxelizer/triangle_soup.h"

namespace dv::test {

inline TriangleSoup soup_of(const std::vector<dvec3>& corners) {
  TriangleSoup s;
  s.corners = corners;
  return s;
}

struct MeshCase {
  const char* name;
  TriangleMesh (*make)();
};

inline TriangleMesh bunny_mesh() {
  return make_bunny(source_dir() + "/experiments/assets", 0);
}
inline TriangleMesh icosphere_mesh() {
  return make_icosphere(0.5, 3);
}
inline TriangleMesh torus_mesh() {
  return make_torus(0.35, 0.15, 48, 24);
}
inline TriangleMesh quad_mesh() {
  return make_subdivided_quad(1.0, 11858);
}

inline const MeshCase kMeshes[] = {{"icosphere", icosphere_mesh},
                                   {"torus", torus_mesh},
                                   {"bunny", bunny_mesh},
                                   {"subdivided_quad", quad_mesh}};

}  // namespace dv::test
