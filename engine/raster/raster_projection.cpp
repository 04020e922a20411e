// Host construction of RasterProjection for cameras, lights and pixel coordinates (see
// raster_projection.h). Every parameter is checked: a bad one throws InputError.
#include "engine/raster/raster_projection.h"

#include <cmath>
#include <string>

#include "core/error.h"
#include "engine/raster/camera_rays.h"

namespace dv {

namespace {

constexpr const char* kWhere = "raster projection";
constexpr double kPi = 3.14159265358979323846;

bool finite(const dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void check_size(int width, int height) {
  if (width < 1 || height < 1 || width > kMaxRasterSide || height > kMaxRasterSide)
    throw InputError(kWhere, "image size " + std::to_string(width) + "x" + std::to_string(height) +
                                 " is outside 1.." + std::to_string(kMaxRasterSide));
}

void check_depth_range(double near_plane, double far_plane) {
  if (!(near_plane > 0.0) || !std::isfinite(near_plane))
    throw InputError(kWhere,
                     "near plane must be a positive number, got " + std::to_string(near_plane));
  if (!(far_plane > near_plane) || !std::isfinite(far_plane))
    throw InputError(kWhere, "far plane must be finite and beyond the near plane (" +
                                 std::to_string(near_plane) + "), got " +
                                 std::to_string(far_plane));
}

struct Basis {
  dvec3 right, up, forward;  // unit, right-handed: right x up = -forward
};

// The same construction as make_camera_view, with a second fallback for lights along x.
Basis view_basis(const dvec3& eye, const dvec3& direction, const dvec3& up_hint) {
  if (!finite(eye) || !finite(direction) || !finite(up_hint))
    throw InputError(kWhere, "eye, direction and up must be finite");
  if (glm::length(direction) < 1e-300) throw InputError(kWhere, "view direction is zero");
  Basis b;
  b.forward = glm::normalize(direction);
  dvec3 right = glm::cross(b.forward, up_hint);
  if (glm::length(right) < 1e-12) right = glm::cross(b.forward, dvec3(1.0, 0.0, 0.0));
  if (glm::length(right) < 1e-12) right = glm::cross(b.forward, dvec3(0.0, 0.0, 1.0));
  b.right = glm::normalize(right);
  b.up = glm::cross(b.right, b.forward);
  return b;
}

// Matrix whose rows are the given affine forms of (p - eye); glm is column-major.
void set_row(dmat4& m, int row, const dvec3& coefficients, double constant, const dvec3& eye) {
  m[0][row] = coefficients.x;
  m[1][row] = coefficients.y;
  m[2][row] = coefficients.z;
  m[3][row] = constant - glm::dot(coefficients, eye);
}

RasterProjection finish(const dmat4& world_to_clip, int width, int height, bool orthographic,
                        const dvec3& eye) {
  RasterProjection p;
  p.world_to_clip = world_to_clip;
  p.clip_to_world = glm::inverse(world_to_clip);
  p.width = width;
  p.height = height;
  p.orthographic = orthographic;
  p.eye = eye;
  return p;
}

// x_row, y_row: clip x and y as linear forms of (p - eye); clip w is the depth along forward.
RasterProjection perspective(const Basis& b, const dvec3& eye, const dvec3& x_row,
                             const dvec3& y_row, double near_plane, double far_plane, int width,
                             int height) {
  const double a = (far_plane + near_plane) / (far_plane - near_plane);
  const double c = -2.0 * far_plane * near_plane / (far_plane - near_plane);
  dmat4 m(0.0);
  set_row(m, 0, x_row, 0.0, eye);
  set_row(m, 1, y_row, 0.0, eye);
  set_row(m, 2, a * b.forward, c, eye);
  set_row(m, 3, b.forward, 0.0, eye);
  RasterProjection p = finish(m, width, height, false, eye);
  p.near_normal = dvec4(0.0, 0.0, 0.0, 1.0);  // clip.w is the depth along forward
  p.near_offset = -near_plane;
  return p;
}

}  // namespace

double fit_far_plane(const dvec3& eye, const dvec3& direction, const Aabb& bounds,
                     double near_plane) {
  double farthest = 0.0;
  if (!bounds.empty()) {
    const dvec3 forward = glm::normalize(direction);
    for (int corner = 0; corner < 8; ++corner) {
      const dvec3 p((corner & 1) ? bounds.hi.x : bounds.lo.x,
                    (corner & 2) ? bounds.hi.y : bounds.lo.y,
                    (corner & 4) ? bounds.hi.z : bounds.lo.z);
      farthest = std::max(farthest, glm::dot(forward, p - eye));
    }
  }
  return std::max(farthest * (1.0 + 1e-6) + 1e-9 * glm::length(bounds.extent()), 2.0 * near_plane);
}

RasterProjection make_camera_projection(const Camera& camera, double far_plane) {
  check_size(camera.width, camera.height);
  check_depth_range(camera.near_plane, far_plane);
  if (!(camera.fov_deg > 0.0 && camera.fov_deg < 180.0))
    throw InputError(kWhere, "camera field of view must be in (0, 180) degrees");
  const CameraView view = make_camera_view(camera);
  const Basis b{glm::normalize(view.right), glm::normalize(view.up), view.forward};
  // camera_ray_direction: d = forward + sx * right + sy * up, so sx = dot(right, d) / |right|^2.
  return perspective(b, camera.position, view.right / glm::dot(view.right, view.right),
                     view.up / glm::dot(view.up, view.up), camera.near_plane, far_plane,
                     camera.width, camera.height);
}

RasterProjection make_camera_projection(const Camera& camera, const Aabb& scene_bounds) {
  const dvec3 direction = camera.target - camera.position;
  if (!finite(direction) || glm::length(direction) < 1e-300)
    throw InputError(kWhere, "camera position and target coincide");
  return make_camera_projection(
      camera, fit_far_plane(camera.position, direction, scene_bounds, camera.near_plane));
}

RasterProjection make_perspective_projection(const dvec3& eye, const dvec3& direction,
                                             const dvec3& up, double fov_y_deg, double aspect,
                                             double near_plane, double far_plane, int width,
                                             int height) {
  check_size(width, height);
  check_depth_range(near_plane, far_plane);
  if (!(fov_y_deg > 0.0 && fov_y_deg < 180.0))
    throw InputError(kWhere,
                     "field of view must be in (0, 180) degrees, got " + std::to_string(fov_y_deg));
  if (!(aspect > 0.0) || !std::isfinite(aspect))
    throw InputError(kWhere, "aspect ratio must be positive, got " + std::to_string(aspect));
  const Basis b = view_basis(eye, direction, up);
  const double half_h = std::tan(0.5 * fov_y_deg * kPi / 180.0);
  const double half_w = half_h * aspect;
  return perspective(b, eye, b.right / half_w, b.up / half_h, near_plane, far_plane, width, height);
}

RasterProjection make_orthographic_projection(const dvec3& eye, const dvec3& direction,
                                              const dvec3& up, double half_width,
                                              double half_height, double near_plane,
                                              double far_plane, int width, int height) {
  check_size(width, height);
  if (!std::isfinite(near_plane) || !(far_plane > near_plane) || !std::isfinite(far_plane))
    throw InputError(kWhere, "orthographic depth range must be finite with far > near");
  if (!(half_width > 0.0) || !(half_height > 0.0) || !std::isfinite(half_width) ||
      !std::isfinite(half_height))
    throw InputError(kWhere, "orthographic half extents must be positive");
  const Basis b = view_basis(eye, direction, up);
  dmat4 m(0.0);
  set_row(m, 0, b.right / half_width, 0.0, eye);
  set_row(m, 1, b.up / half_height, 0.0, eye);
  set_row(m, 2, b.forward * (2.0 / (far_plane - near_plane)),
          -(far_plane + near_plane) / (far_plane - near_plane), eye);
  m[3][3] = 1.0;
  RasterProjection p = finish(m, width, height, true, eye);
  p.near_normal = dvec4(0.0, 0.0, 1.0, 1.0);  // z_ndc >= -1
  p.near_offset = 0.0;
  return p;
}

RasterProjection make_screen_projection(int width, int height) {
  check_size(width, height);
  dmat4 m(0.0);
  m[0][0] = 2.0 / double(width);
  m[3][0] = -1.0;
  m[1][1] = -2.0 / double(height);
  m[3][1] = 1.0;
  m[2][2] = 1.0;
  m[3][3] = 1.0;
  RasterProjection p = finish(m, width, height, true, dvec3(0.0));
  p.near_normal = dvec4(0.0);
  p.near_offset = 1.0;
  return p;
}

}  // namespace dv
