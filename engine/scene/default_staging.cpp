// Default camera, lights and ground plane for scenes that bring none (see default_staging.h).
#include "engine/scene/default_staging.h"

#include <algorithm>
#include <cmath>

namespace dv {

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// Bounding-sphere radius of a box, never zero.
double bounding_radius(const Aabb& bounds) {
  return bounds.empty() ? 1.0 : std::max(0.5 * glm::length(bounds.extent()), 1e-3);
}

dvec3 centre_of(const Aabb& bounds) {
  return bounds.empty() ? dvec3(0.0) : bounds.center();
}

// Unit vector from the centre towards a point at `azimuth` (from +z towards +x) and
// `elevation` degrees.
dvec3 direction_from(double azimuth_deg, double elevation_deg) {
  const double a = azimuth_deg * kDeg, e = elevation_deg * kDeg;
  return {std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a)};
}

}  // namespace

Camera default_camera(const Aabb& bounds) {
  Camera c;
  const double radius = bounding_radius(bounds);
  c.fov_deg = 45.0;
  const double distance = radius / std::sin(0.5 * c.fov_deg * kDeg);
  c.target = centre_of(bounds);
  c.position =
      c.target + distance * direction_from(kDefaultViewAzimuthDeg, kDefaultViewElevationDeg);
  c.near_plane = std::min(0.01, 0.5 * (distance - radius));
  return c;
}

std::vector<Light> default_lights(const Aabb& bounds) {
  const dvec3 centre = centre_of(bounds);
  const double radius = bounding_radius(bounds);
  Light key;
  key.type = LightType::spot;
  const double distance = 4.0 * radius;
  key.position = centre + distance * direction_from(kDefaultViewAzimuthDeg - 60.0, 55.0);
  key.direction = glm::normalize(centre - key.position);
  // The cone reaches 2.5 radii from the centre at the light's distance: the model and the
  // ground plane's lit area around it.
  key.penumbra_deg = 12.0;
  key.cutoff_deg = std::atan(2.5 * radius / distance) / kDeg + key.penumbra_deg;
  key.intensity = distance * distance;  // irradiance 1 at the centre
  Light fill;
  fill.type = LightType::directional;
  fill.direction = -direction_from(kDefaultViewAzimuthDeg, kDefaultViewElevationDeg);
  fill.intensity = 0.25;
  return {key, fill};
}

void add_ground_plane(Scene& scene) {
  for (const Object& o : scene.objects)
    if (o.name == "ground") return;
  const Aabb bounds = world_bounds(scene);
  const dvec3 centre = centre_of(bounds);
  const double half = 3.0 * bounding_radius(bounds);
  // A hair below the bounds so the model's own bottom faces never tie with the ground.
  const double y = (bounds.empty() ? 0.0 : bounds.lo.y) - 1e-4 * half;
  TriangleMesh mesh;
  mesh.name = "ground";
  mesh.positions = {{centre.x - half, y, centre.z - half},
                    {centre.x + half, y, centre.z - half},
                    {centre.x + half, y, centre.z + half},
                    {centre.x - half, y, centre.z + half}};
  mesh.triangles = {{0u, 2u, 1u}, {0u, 3u, 2u}};
  Object ground;
  ground.name = "ground";
  ground.mesh = int(scene.meshes.size());
  ground.material.color = dvec3(0.6);
  ground.material.specular = 0.0;
  scene.meshes.push_back(std::move(mesh));
  scene.objects.push_back(std::move(ground));
}

}  // namespace dv
