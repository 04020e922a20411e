// The voxelizers' input: independent world-space triangles (three corners each), gathered from
// every object of a scene with its transform applied. Open and closed meshes are treated alike:
// each triangle is voxelized as it is.
#pragma once

#include <cstdint>
#include <vector>

#include "core/math.h"
#include "engine/scene/scene.h"

namespace dv {

struct TriangleSoup {
  std::vector<dvec3> corners;  // 3 per triangle, world space

  int64_t triangle_count() const { return int64_t(corners.size() / 3); }
  void add(const dvec3& a, const dvec3& b, const dvec3& c) {
    corners.push_back(a);
    corners.push_back(b);
    corners.push_back(c);
  }
  Aabb bounds() const;
};

TriangleSoup triangle_soup(const TriangleMesh& mesh, const dmat4& transform = dmat4(1.0));
TriangleSoup triangle_soup(const Scene& scene);

}  // namespace dv
