// Pinhole camera rays for host and device: one ray through each pixel centre.
#pragma once

#include <cmath>

#include "core/hd.h"
#include "core/math.h"
#include "engine/scene/scene.h"

namespace dv {

struct CameraView {
  dvec3 position;
  dvec3 forward;  // unit
  dvec3 right;    // scaled: pixel x in [-1, 1] maps to +-right
  dvec3 up;       // scaled likewise
  int width, height;
  double near_plane;
};

inline CameraView make_camera_view(const Camera& c) {
  CameraView v;
  v.position = c.position;
  v.forward = glm::normalize(c.target - c.position);
  dvec3 right = glm::cross(v.forward, c.up);
  if (glm::length(right) < 1e-12) right = glm::cross(v.forward, dvec3(1.0, 0.0, 0.0));
  right = glm::normalize(right);
  const dvec3 up = glm::cross(right, v.forward);
  const double half_h = std::tan(0.5 * c.fov_deg * 3.14159265358979323846 / 180.0);
  const double half_w = half_h * double(c.width) / double(c.height);
  v.right = right * half_w;
  v.up = up * half_h;
  v.width = c.width;
  v.height = c.height;
  v.near_plane = c.near_plane;
  return v;
}

DV_HD inline dvec3 camera_ray_direction(const CameraView& c, int x, int y) {
  const double sx = (double(x) + 0.5) / double(c.width) * 2.0 - 1.0;
  const double sy = 1.0 - (double(y) + 0.5) / double(c.height) * 2.0;
  return glm::normalize(c.forward + sx * c.right + sy * c.up);
}

// Camera on a circle of `degrees` total arc about the target's vertical axis: frame i of n.
Camera orbit_camera(const Camera& base, double degrees, int frame, int frames);

// A camera moved from `base` the way the viewer's mouse moves it (`render --view` replays it):
// the offset from the target turned by yaw about the up axis, then by pitch about the camera's
// right axis (clamped short of the poles), scaled by dolly (> 0), and camera and target shifted
// by pan_x right and pan_y up, in units of the base camera's distance to its target.
struct CameraMove {
  double yaw_deg = 0.0;
  double pitch_deg = 0.0;
  double dolly = 1.0;
  double pan_x = 0.0;
  double pan_y = 0.0;
};
Camera moved_camera(const Camera& base, const CameraMove& move);

}  // namespace dv
