// make_light_grid (see frustum_grid.h).
#include "strategies/voxelizer/frustum_grid.h"

#include <algorithm>
#include <cmath>

namespace dv {

GridSpec make_light_grid(const ShadowFace& face, int res, int depth, const Aabb& casters,
                         const std::string& where) {
  GridSpec spec;
  spec.kind = face.orthographic ? GridKind::orthographic : GridKind::perspective;
  spec.res = ivec3(res, res, depth);
  GridFrustum& f = spec.frustum;
  f.projection = face.projection;
  f.projection.width = res;
  f.projection.height = res;
  f.eye = face.eye;
  f.axis = face.axis;
  double lo = INFINITY, hi = -INFINITY;
  if (!casters.empty())
    for (int corner = 0; corner < 8; ++corner) {
      const dvec3 c(corner & 1 ? casters.hi.x : casters.lo.x,
                    corner & 2 ? casters.hi.y : casters.lo.y,
                    corner & 4 ? casters.hi.z : casters.lo.z);
      const double d = glm::dot(c - face.eye, face.axis);
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  if (!(hi >= lo)) lo = hi = 0.0;
  if (!face.orthographic) {  // nothing behind the light is in the grid
    lo = std::max(lo, 0.0);
    hi = std::max(hi, lo);
  }
  const double pad = 1e-6 * std::max({hi - lo, std::abs(hi), std::abs(lo), 1e-9});
  f.near = lo - pad;
  f.far = hi + pad;
  if (!face.orthographic) f.near = std::max(f.near, 1e-6 * f.far);
  // Bounding box of the frustum between the near and the far depth.
  for (int corner = 0; corner < 4; ++corner) {
    const PixelRay ray = image_point_ray(f.projection, corner & 1 ? double(res) : 0.0,
                                         corner & 2 ? double(res) : 0.0);
    const double start = glm::dot(ray.origin - f.eye, f.axis);
    const double along = glm::dot(ray.direction, f.axis);
    for (double d : {f.near, f.far})
      spec.bounds.extend(ray.origin + ray.direction * ((d - start) / along));
  }
  validate_grid_spec(spec, where);
  return spec;
}

}  // namespace dv
