// Orbiting cameras for multi-frame renders and the viewer's camera moves (see camera_rays.h).
#include "engine/raster/camera_rays.h"

#include <algorithm>

namespace dv {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Rodrigues rotation of v about the unit axis by `radians`.
dvec3 rotate(const dvec3& v, const dvec3& axis, double radians) {
  return v * std::cos(radians) + glm::cross(axis, v) * std::sin(radians) +
         axis * glm::dot(axis, v) * (1.0 - std::cos(radians));
}

}  // namespace

Camera orbit_camera(const Camera& base, double degrees, int frame, int frames) {
  if (frames <= 1 || degrees == 0.0) return base;
  const double angle = degrees * kPi / 180.0 * double(frame) / double(frames);
  Camera c = base;
  c.position = base.target + rotate(base.position - base.target, glm::normalize(base.up), angle);
  return c;
}

Camera moved_camera(const Camera& base, const CameraMove& move) {
  const dvec3 up = glm::normalize(base.up);
  const dvec3 base_offset = base.position - base.target;
  const double distance = glm::length(base_offset);
  dvec3 offset = rotate(base_offset, up, move.yaw_deg * kPi / 180.0);
  const CameraView yawed =
      make_camera_view(Camera{base.target + offset, base.target, base.up, base.fov_deg, base.width,
                              base.height, base.near_plane});
  const dvec3 right = glm::normalize(yawed.right);
  const dvec3 view_up = glm::normalize(yawed.up);
  // Elevation of the offset above the plane normal to up, kept within 89 degrees of it.
  const double elevation = std::asin(std::clamp(glm::dot(glm::normalize(offset), up), -1.0, 1.0));
  const double limit = 89.0 * kPi / 180.0;
  const double pitch =
      std::clamp(elevation + move.pitch_deg * kPi / 180.0, -limit, limit) - elevation;
  offset = rotate(offset, right, -pitch) * move.dolly;
  Camera c = base;
  c.target = base.target + (right * move.pan_x + view_up * move.pan_y) * distance;
  c.position = c.target + offset;
  return c;
}

}  // namespace dv
