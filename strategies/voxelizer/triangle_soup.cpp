// Flattening of meshes and scenes into world-space triangle soups (see triangle_soup.h).
#include "strategies/voxelizer/triangle_soup.h"

#include "core/error.h"

namespace dv {

Aabb TriangleSoup::bounds() const {
  Aabb box;
  for (const dvec3& p : corners) box.extend(p);
  return box;
}

TriangleSoup triangle_soup(const TriangleMesh& mesh, const dmat4& transform) {
  TriangleSoup soup;
  soup.corners.reserve(mesh.triangles.size() * 3);
  std::vector<dvec3> world(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    world[i] = dvec3(transform * dvec4(mesh.positions[i], 1.0));
  for (const u32vec3& t : mesh.triangles) {
    if (t.x >= world.size() || t.y >= world.size() || t.z >= world.size())
      throw InputError(mesh.name, "triangle index beyond the vertex list");
    soup.add(world[t.x], world[t.y], world[t.z]);
  }
  return soup;
}

TriangleSoup triangle_soup(const Scene& scene) {
  TriangleSoup soup;
  for (const Object& obj : scene.objects) {
    TriangleSoup part = triangle_soup(scene.meshes[size_t(obj.mesh)], obj.transform);
    soup.corners.insert(soup.corners.end(), part.corners.begin(), part.corners.end());
  }
  return soup;
}

}  // namespace dv
