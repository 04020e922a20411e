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

std::vector<Light> default_lights(const Aabb& casters, const Camera& camera,
                                  std::optional<double> ground_y) {
  const dvec3 centre = centre_of(casters);
  const double radius = bounding_radius(casters);
  const dvec3 from_centre = camera.position - centre;
  const bool looks_down = std::hypot(from_centre.x, from_centre.z) <= 1e-9 * radius;
  const double camera_azimuth =
      looks_down ? kDefaultViewAzimuthDeg : std::atan2(from_centre.x, from_centre.z) / kDeg;
  Light key;
  key.type = LightType::spot;
  const double distance = kKeyDistanceRadii * radius;
  key.position = centre + distance * direction_from(camera_azimuth + kKeyAzimuthFromCameraDeg,
                                                    kKeyElevationDeg);
  key.direction = glm::normalize(centre - key.position);
  key.intensity = distance * distance;  // irradiance 1 at the centre
  // The widest tangent from the axis over the points the core must light.
  double widest = 0.0;
  auto include = [&](const dvec3& p) {
    const dvec3 d = p - key.position;
    const double along = glm::dot(d, key.direction);
    if (along > 0.0) widest = std::max(widest, glm::length(d - along * key.direction) / along);
  };
  const Aabb box = casters.empty() ? Aabb{centre - dvec3(radius), centre + dvec3(radius)} : casters;
  for (int corner = 0; corner < 8; ++corner) {
    const dvec3 c(corner & 1 ? box.hi.x : box.lo.x, corner & 2 ? box.hi.y : box.lo.y,
                  corner & 4 ? box.hi.z : box.lo.z);
    include(c);
    // The corner's shadow on the ground (the key stands above the casters' bounds).
    if (ground_y && c.y < key.position.y) {
      const double t = (key.position.y - *ground_y) / (key.position.y - c.y);
      include(key.position + t * (c - key.position));
    }
  }
  // 3 % beyond the model; 30 % of lit ground around the model and its shadow.
  const double core_deg = std::atan(widest * (ground_y ? 1.3 : 1.03)) / kDeg;
  key.penumbra_deg = std::max(1.0, 0.1 * core_deg);
  key.cutoff_deg = std::min(core_deg + key.penumbra_deg, 89.0);
  Light fill;
  fill.type = LightType::directional;
  fill.direction = glm::normalize(camera.target - camera.position);
  fill.intensity = 0.25;
  return {key, fill};
}

std::optional<double> add_ground_plane(Scene& scene) {
  for (const Object& o : scene.objects)
    if (o.name == "ground") return std::nullopt;
  const Aabb bounds = world_bounds(scene);
  const dvec3 centre = centre_of(bounds);
  const double radius = bounding_radius(bounds), half = 3.0 * radius;
  const double y = (bounds.empty() ? 0.0 : bounds.lo.y) - kGroundGapRadii * radius;
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
  return y;
}

bool stage_scene(Scene& scene, const StagingOptions& options) {
  const bool staged = options.lights && scene.lights.empty();
  const bool ground =
      options.ground == GroundPlane::on || (options.ground == GroundPlane::staged && staged);
  const Aabb casters = world_bounds(scene);
  const std::optional<double> ground_y = ground ? add_ground_plane(scene) : std::nullopt;
  if (staged) scene.lights = default_lights(casters, scene.camera, ground_y);
  return staged;
}

}  // namespace dv
