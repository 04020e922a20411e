// Set voxels of a light grid as world-space points (see viewer_voxel_overlay.h).
#include "apps/viewer/viewer_voxel_overlay.h"

#include <bit>

#include "engine/raster/raster_projection.h"

namespace dv::viewer {

dvec3 voxel_centre(const GridSpec& spec, int x, int y, int z) {
  if (spec.kind == GridKind::box)
    return spec.bounds.lo + (dvec3(x, y, z) + 0.5) * spec.voxel_size();
  const GridFrustum& f = spec.frustum;
  const PixelRay ray = image_point_ray(f.projection, x + 0.5, y + 0.5);
  const double depth = f.near + (z + 0.5) * (f.far - f.near) / double(spec.res.z);
  const double start = glm::dot(ray.origin - f.eye, f.axis);
  return ray.origin + ray.direction * ((depth - start) / glm::dot(ray.direction, f.axis));
}

void add_set_voxels(const VoxelGrid& grid, VoxelPoints& out) {
  const GridSpec& spec = grid.spec();
  const std::vector<uint32_t> words = grid.words();
  const VoxelGridView view{const_cast<uint32_t*>(words.data()), spec.res.x, spec.res.y, spec.res.z};
  for (int k = 0; k < spec.words_per_column(); ++k)
    for (int y = 0; y < spec.res.y; ++y)
      for (int x = 0; x < spec.res.x; ++x)
        for (uint32_t bits = words[size_t(view.word_index(x, y, k))]; bits; bits &= bits - 1) {
          const int z = k * 32 + std::countr_zero(bits);
          const dvec3 c = voxel_centre(spec, x, y, z);
          out.positions.insert(out.positions.end(), {float(c.x), float(c.y), float(c.z)});
          out.depths.push_back(float((z + 0.5) / spec.res.z));
        }
  ++out.grids;
}

}  // namespace dv::viewer
