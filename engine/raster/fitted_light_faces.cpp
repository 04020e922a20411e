// Light-map faces fitted to the objects that can cast a shadow (see fitted_light_faces.h).
#include "engine/raster/fitted_light_faces.h"

namespace dv {

double light_map_near(double diagonal) {
  return 1e-4 * diagonal + 1e-9;
}

ShadowFace orthographic_light_face(const LightView& l, const dvec3& centre, double radius,
                                   const dvec3& depth_centre, double depth_radius, double diagonal,
                                   int res) {
  const double near_min = light_map_near(diagonal);
  const double front = glm::dot(depth_centre - centre, l.direction) - depth_radius;
  const dvec3 eye = centre + l.direction * (front - 2.0 * near_min);
  return {make_orthographic_projection(eye, l.direction, dvec3(0, 1, 0), radius, radius, near_min,
                                       2.0 * depth_radius + 3.0 * near_min, res, res),
          eye + l.direction * near_min,
          l.direction,
          true,
          2.0 * radius / res,
          0};
}

namespace {

// True when object `plane` is flat along some axis and every other object lies on the side of
// that plane the light comes from.
bool shadows_nothing(const LightView& l, const std::vector<Aabb>& objects, size_t plane) {
  const Aabb& p = objects[plane];
  if (p.empty()) return false;
  const double size = glm::length(p.extent());
  for (int axis = 0; axis < 3; ++axis) {
    if (p.hi[axis] - p.lo[axis] > 1e-12 * size || l.direction[axis] == 0.0) continue;
    const bool from_above = l.direction[axis] < 0.0;  // the light travels towards -axis
    const double at = p.lo[axis];
    bool all_lit_side = true;
    for (size_t i = 0; i < objects.size() && all_lit_side; ++i)
      if (i != plane && !objects[i].empty())
        all_lit_side = from_above ? objects[i].lo[axis] >= at : objects[i].hi[axis] <= at;
    if (all_lit_side) return true;
  }
  return false;
}

}  // namespace

Aabb directional_casters(const LightView& l, const Aabb& bounds, const std::vector<Aabb>& objects) {
  Aabb casters;
  for (size_t i = 0; i < objects.size(); ++i)
    if (!shadows_nothing(l, objects, i)) casters.extend(objects[i]);
  return casters.empty() ? bounds : casters;
}

std::vector<ShadowFace> fitted_light_map_faces(const LightView& l, const Aabb& bounds,
                                               const std::vector<Aabb>& objects, double diagonal,
                                               int res) {
  if (l.type != LightType::directional) return light_map_faces(l, bounds, diagonal, res);
  bool any_left_out = false;
  for (size_t i = 0; i < objects.size(); ++i) any_left_out |= shadows_nothing(l, objects, i);
  if (!any_left_out) return light_map_faces(l, bounds, diagonal, res);
  const Aabb casters = directional_casters(l, bounds, objects);
  return {orthographic_light_face(l, casters.center(), 0.5 * glm::length(casters.extent()) + 1e-9,
                                  bounds.center(), 0.5 * diagonal + 1e-9, diagonal, res)};
}

LightMapLayout layout_light_faces(const std::vector<std::vector<ShadowFace>>& per_light, int res) {
  LightMapLayout layout;
  layout.texels_per_face = int64_t(res) * res;
  for (const std::vector<ShadowFace>& f : per_light) {
    layout.lights.push_back({int32_t(layout.faces.size()), int32_t(f.size())});
    layout.faces.insert(layout.faces.end(), f.begin(), f.end());
  }
  for (size_t i = 0; i < layout.faces.size(); ++i)
    layout.faces[i].offset = int64_t(i) * layout.texels_per_face;
  return layout;
}

LightMapLayout fitted_light_map_layout(const std::vector<LightView>& lights, const Aabb& bounds,
                                       const std::vector<Aabb>& objects, double diagonal, int res) {
  std::vector<std::vector<ShadowFace>> per_light;
  for (const LightView& l : lights)
    per_light.push_back(fitted_light_map_faces(l, bounds, objects, diagonal, res));
  return layout_light_faces(per_light, res);
}

}  // namespace dv
