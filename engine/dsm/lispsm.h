// Light-space perspective transform (Wimmer et al. 2004; Knecht 2011 §2.4.2, §4.5, Algorithm
// 4.3) as the clustering uses it: the space in which objects' boxes are compared, so that the
// distances (and hence the clusters) follow what the camera sees.
//
// Per light face: the convex body B = hull(light position, camera frustum) clipped by the scene
// bounds and the face's frustum (CGAL::convex_hull_3, then each plane cuts the hull's edges).
// The face's perspective is applied first (Knecht: a point light becomes a directional one along
// +z of the face's NDC). Light space: y = the inverse light vector, z = the camera's view vector
// made perpendicular to it, x completes the basis. P looks along z from (x of the camera,
// middle of B in y, n before B's near extent) and spans B; n = n_opt = z_n + sqrt(z_n z_f) of
// the camera, with the camera's depth range [z_n, z_f] mapped onto B's depth. A point maps to
// (x, z) after P, both in [-1, 1] over B: the warped shadow map's plane. When the view is
// parallel to the light (no warp possible) the map is the face's own NDC x, y. Objects whose
// box misses B cast no shadow the camera can see.
// Host only.
#pragma once

#include <vector>

#include "core/math.h"
#include "engine/raster/light_faces.h"
#include "engine/scene/scene.h"

namespace dv {

// A half-space h.x * p.x + h.y * p.y + h.z * p.z + h.w >= 0.
using HalfSpace = dvec4;

// Vertices of hull(points) intersected with every half-space (empty when nothing is left).
std::vector<dvec3> clipped_convex_hull(const std::vector<dvec3>& points,
                                       const std::vector<HalfSpace>& half_spaces);

struct LispsmSpace {
  bool empty = true;  // B is empty: nothing this face lights is seen
  bool warped = false;
  Aabb body_bounds;  // world bounds of B
  RasterProjection face;
  dvec3 x_axis{1, 0, 0}, y_axis{0, -1, 0}, z_axis{0, 0, 1};  // light space in the face's NDC
  dvec3 eye{0.0};                                            // P's eye in light space
  double n = 1.0, f = 2.0;                                   // P's near and far (along z)
  double u_lo = -1.0, u_hi = 1.0;                            // P's x/z over B

  // Where a box falls on the warped map plane, clipped to [-1, 1]^2: lo, hi; false when the box
  // misses B (or, unwarped, the face).
  bool box_rect(const Aabb& box, dvec2& lo, dvec2& hi) const;
};

// The space of one light face for `camera` (far plane fitted to the scene bounds).
LispsmSpace lispsm_space(const ShadowFace& face, const LightView& light, const Camera& camera,
                         const Aabb& scene_bounds, double diagonal);

}  // namespace dv
