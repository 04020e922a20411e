// Host construction of light-map faces (see light_faces.h).
#include "engine/raster/light_faces.h"

#include <cmath>

#include "engine/raster/fitted_light_faces.h"

namespace dv {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

std::vector<ShadowFace> light_map_faces(const LightView& l, const Aabb& bounds, double diagonal,
                                        int res) {
  const double near_min = light_map_near(diagonal);
  std::vector<ShadowFace> faces;
  auto perspective = [&](const dvec3& dir, const dvec3& up, double fov) {
    const double far = fit_far_plane(l.position, dir, bounds, near_min);
    const double texel = 2.0 * std::tan(0.5 * fov * kPi / 180.0) / res;
    faces.push_back(
        {make_perspective_projection(l.position, dir, up, fov, 1.0, near_min, far, res, res),
         l.position, dir, false, texel, 0});
  };
  if (l.type == LightType::spot) {
    perspective(l.direction, dvec3(0, 1, 0), 2.0 * std::acos(l.cos_cutoff) * 180.0 / kPi);
  } else if (l.type == LightType::omni) {
    const dvec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const dvec3& a : axes) perspective(a, a.y != 0.0 ? dvec3(0, 0, 1) : dvec3(0, 1, 0), 90.0);
  } else {
    // Orthographic box around the casters: centred on the bounds, as wide as their sphere.
    const double radius = 0.5 * diagonal + 1e-9;
    faces.push_back(orthographic_light_face(l, bounds.center(), radius, bounds.center(), radius,
                                            diagonal, res));
  }
  return faces;
}

LightMapLayout light_map_layout(const std::vector<LightView>& lights, const Aabb& bounds,
                                double diagonal, int res) {
  std::vector<std::vector<ShadowFace>> per_light;
  for (const LightView& l : lights) per_light.push_back(light_map_faces(l, bounds, diagonal, res));
  return layout_light_faces(per_light, res);
}

std::vector<LightView> mapped_lights(const std::vector<LightView>& lights, int light) {
  if (light < 0) return lights;
  return {lights.at(size_t(light))};
}

}  // namespace dv
