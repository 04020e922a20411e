// Where the rasterizer looks from: a world -> clip matrix, its inverse, the near plane and the
// image size, as a plain struct that kernels receive by value. Host helpers build it for the
// scene camera (matching engine/raster/camera_rays.h exactly), for lights (perspective and
// orthographic, for shadow maps and deep shadow maps) and for plain pixel coordinates (tests,
// 2-D work). pixel_ray() gives the world-space ray through a pixel centre, so per-pixel code that
// intersects triangles agrees with the rasterizer on where pixel centres are.
//
// Conventions (OpenGL-like): clip = world_to_clip * (p, 1); NDC = clip.xyz / clip.w with x to
// the right, y up, z in [-1, 1] between the near and the far plane. Pixel (x, y) has its centre
// at NDC ((x + 0.5) / width * 2 - 1, 1 - (y + 0.5) / height * 2): image rows go down. A point is
// in front of the near plane when dot(near_normal, clip) + near_offset >= 0 (perspective:
// clip.w >= near; orthographic: clip.z >= -clip.w). The far plane only scales z: nothing is
// clipped against it.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "core/math.h"
#include "engine/scene/scene.h"

namespace dv {

// Largest image side the rasterizer accepts (keeps fixed-point coordinates small; see
// engine/raster/tile_raster.h).
inline constexpr int kMaxRasterSide = 1 << 16;

struct RasterProjection {
  dmat4 world_to_clip{1.0};
  dmat4 clip_to_world{1.0};
  dvec4 near_normal{0.0, 0.0, 0.0, 1.0};
  double near_offset = 0.0;
  int width = 0;
  int height = 0;
  bool orthographic = false;
  dvec3 eye{0.0};  // perspective: the centre of projection
};

struct PixelRay {
  dvec3 origin;     // perspective: the eye; orthographic: the point on the near plane
  dvec3 direction;  // unit
};

DV_HD inline dvec4 world_to_clip_point(const RasterProjection& p, const dvec3& w) {
  const dmat4& m = p.world_to_clip;
  dvec4 c;
  for (int r = 0; r < 4; ++r) c[r] = ((m[0][r] * w.x + m[1][r] * w.y) + m[2][r] * w.z) + m[3][r];
  return c;
}

DV_HD inline double near_plane_distance(const RasterProjection& p, const dvec4& clip) {
  return ((p.near_normal.x * clip.x + p.near_normal.y * clip.y) + p.near_normal.z * clip.z +
          p.near_normal.w * clip.w) +
         p.near_offset;
}

// NDC (x, y) of image position (px, py) in pixels (x right, y down; pixel (x, y)'s centre is
// (x + 0.5, y + 0.5)).
DV_HD inline dvec2 image_point_ndc(const RasterProjection& p, double px, double py) {
  return {px / double(p.width) * 2.0 - 1.0, 1.0 - py / double(p.height) * 2.0};
}

DV_HD inline dvec3 unproject_ndc(const RasterProjection& p, double x, double y, double z) {
  const dvec4 h = p.clip_to_world * dvec4(x, y, z, 1.0);
  return dvec3(h.x, h.y, h.z) / h.w;
}

// World-space ray through image position (px, py): along the line from the near plane to the
// far plane; it starts at the eye for perspective projections.
DV_HD inline PixelRay image_point_ray(const RasterProjection& p, double px, double py) {
  const dvec2 ndc = image_point_ndc(p, px, py);
  const dvec3 on_near = unproject_ndc(p, ndc.x, ndc.y, -1.0);
  const dvec3 on_far = unproject_ndc(p, ndc.x, ndc.y, 1.0);
  return {p.orthographic ? on_near : p.eye, glm::normalize(on_far - on_near)};
}

// The ray through the centre of pixel (x, y).
DV_HD inline PixelRay pixel_ray(const RasterProjection& p, int x, int y) {
  return image_point_ray(p, double(x) + 0.5, double(y) + 0.5);
}

// The scene camera (same pixel centres and basis as make_camera_view) with the given far plane.
RasterProjection make_camera_projection(const Camera& camera, double far_plane);
// The same with the far plane fitted to `scene_bounds` (a little beyond its farthest corner).
RasterProjection make_camera_projection(const Camera& camera, const Aabb& scene_bounds);

// A perspective view from `eye` along `direction` (`up` is a hint, replaced when parallel):
// vertical field of view fov_y_deg, frustum width/height ratio `aspect`.
RasterProjection make_perspective_projection(const dvec3& eye, const dvec3& direction,
                                             const dvec3& up, double fov_y_deg, double aspect,
                                             double near_plane, double far_plane, int width,
                                             int height);
// An orthographic box along `direction` through `eye`: x in [-half_width, half_width] and y in
// [-half_height, half_height] about the axis, depth from near_plane to far_plane beyond `eye`.
RasterProjection make_orthographic_projection(const dvec3& eye, const dvec3& direction,
                                              const dvec3& up, double half_width,
                                              double half_height, double near_plane,
                                              double far_plane, int width, int height);
// World x and y are pixel coordinates (x right, y down, pixel centres at k + 0.5); z is ignored
// and nothing is behind the near plane.
RasterProjection make_screen_projection(int width, int height);

// Distance along unit `direction` from `eye` to the farthest corner of `bounds`, widened a
// little and at least 2 * near_plane (a box behind the eye gives 2 * near_plane).
double fit_far_plane(const dvec3& eye, const dvec3& direction, const Aabb& bounds,
                     double near_plane);

}  // namespace dv
