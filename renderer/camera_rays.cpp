// Orbiting cameras for multi-frame renders (see camera_rays.h).
#include "renderer/camera_rays.h"

namespace dv {

Camera orbit_camera(const Camera& base, double degrees, int frame, int frames) {
  if (frames <= 1 || degrees == 0.0) return base;
  const double angle = degrees * 3.14159265358979323846 / 180.0 * double(frame) / double(frames);
  const dvec3 axis = glm::normalize(base.up);
  const dvec3 offset = base.position - base.target;
  // Rodrigues rotation of the offset about the up axis through the target.
  const dvec3 rotated = offset * std::cos(angle) + glm::cross(axis, offset) * std::sin(angle) +
                        axis * glm::dot(axis, offset) * (1.0 - std::cos(angle));
  Camera c = base;
  c.position = base.target + rotated;
  return c;
}

}  // namespace dv
