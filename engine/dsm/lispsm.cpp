// Light-space perspective transform for clustering (see lispsm.h).
#include "engine/dsm/lispsm.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <cmath>

namespace dv {

namespace {

using HullKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using HullPoint = HullKernel::Point_3;
using HullMesh = CGAL::Surface_mesh<HullPoint>;

double side(const HalfSpace& h, const dvec3& p) {
  return h.x * p.x + h.y * p.y + h.z * p.z + h.w;
}

// Whether the points span a volume (convex_hull_3 then gives a closed mesh with edges).
bool spans_volume(const std::vector<dvec3>& p) {
  if (p.size() < 4) return false;
  double scale = 0.0;
  for (const dvec3& q : p) scale = std::max(scale, glm::length(q - p[0]));
  size_t a = 0, b = 0;
  double best = 0.0;
  for (size_t i = 1; i < p.size(); ++i)
    if (glm::length(p[i] - p[0]) > best) best = glm::length(p[i] - p[0]), a = i;
  best = 0.0;
  for (size_t i = 1; i < p.size(); ++i) {
    const double area = glm::length(glm::cross(p[a] - p[0], p[i] - p[0]));
    if (area > best) best = area, b = i;
  }
  const dvec3 normal = glm::cross(p[a] - p[0], p[b] - p[0]);
  double volume = 0.0;
  for (const dvec3& q : p) volume = std::max(volume, std::abs(glm::dot(normal, q - p[0])));
  return volume > 1e-9 * scale * scale * scale;
}

// Segments whose crossings with a plane bound the clipped hull: the hull's edges, or every pair
// when the points are flat.
std::vector<std::pair<dvec3, dvec3>> hull_edges(const std::vector<dvec3>& p) {
  std::vector<std::pair<dvec3, dvec3>> edges;
  if (!spans_volume(p)) {
    for (size_t i = 0; i < p.size(); ++i)
      for (size_t j = i + 1; j < p.size(); ++j) edges.push_back({p[i], p[j]});
    return edges;
  }
  std::vector<HullPoint> points;
  for (const dvec3& q : p) points.emplace_back(q.x, q.y, q.z);
  HullMesh mesh;
  CGAL::convex_hull_3(points.begin(), points.end(), mesh);
  for (HullMesh::Edge_index e : mesh.edges()) {
    const HullPoint& a = mesh.point(mesh.vertex(e, 0));
    const HullPoint& b = mesh.point(mesh.vertex(e, 1));
    edges.push_back({dvec3(a.x(), a.y(), a.z()), dvec3(b.x(), b.y(), b.z())});
  }
  return edges;
}

}  // namespace

std::vector<dvec3> clipped_convex_hull(const std::vector<dvec3>& points,
                                       const std::vector<HalfSpace>& half_spaces) {
  std::vector<dvec3> p = points;
  for (const HalfSpace& h : half_spaces) {
    if (p.empty()) return p;
    if (std::all_of(p.begin(), p.end(), [&](const dvec3& q) { return side(h, q) >= 0.0; }))
      continue;
    std::vector<dvec3> kept;
    for (const dvec3& q : p)
      if (side(h, q) >= 0.0) kept.push_back(q);
    for (const auto& [a, b] : hull_edges(p)) {
      const double da = side(h, a), db = side(h, b);
      if ((da >= 0.0) != (db >= 0.0)) kept.push_back(a + (b - a) * (da / (da - db)));
    }
    p = std::move(kept);
  }
  return p;
}

namespace {

// The half-spaces of a face's frustum sides and near plane (clip-space planes carried to world).
std::vector<HalfSpace> frustum_half_spaces(const RasterProjection& p) {
  const dmat4 t = glm::transpose(p.world_to_clip);
  std::vector<HalfSpace> out;
  for (const dvec4& clip_plane :
       {dvec4(1, 0, 0, 1), dvec4(-1, 0, 0, 1), dvec4(0, 1, 0, 1), dvec4(0, -1, 0, 1)})
    out.push_back(t * clip_plane);
  out.push_back(t * p.near_normal + dvec4(0, 0, 0, p.near_offset));
  return out;
}

std::vector<HalfSpace> box_half_spaces(const Aabb& b) {
  return {{1, 0, 0, -b.lo.x}, {-1, 0, 0, b.hi.x}, {0, 1, 0, -b.lo.y},
          {0, -1, 0, b.hi.y}, {0, 0, 1, -b.lo.z}, {0, 0, -1, b.hi.z}};
}

// NDC of the face; false behind a perspective face's eye.
bool face_ndc(const RasterProjection& p, const dvec3& world, dvec3& ndc) {
  const dvec4 c = world_to_clip_point(p, world);
  if (!p.orthographic && c.w <= 0.0) return false;
  ndc = dvec3(c) / c.w;
  return true;
}

}  // namespace

LispsmSpace lispsm_space(const ShadowFace& face, const LightView& light, const Camera& camera,
                         const Aabb& scene_bounds, double diagonal) {
  LispsmSpace s;
  s.face = face.projection;
  const RasterProjection view = make_camera_projection(camera, scene_bounds);
  std::vector<dvec3> points;
  for (int c = 0; c < 8; ++c)
    points.push_back(
        unproject_ndc(view, (c & 1) ? 1.0 : -1.0, (c & 2) ? 1.0 : -1.0, (c & 4) ? 1.0 : -1.0));
  // A directional light sits far beyond the scene against its direction.
  points.push_back(light.type == LightType::directional
                       ? scene_bounds.center() - light.direction * (1e3 * diagonal)
                       : light.position);
  std::vector<HalfSpace> planes = box_half_spaces(scene_bounds);
  for (const HalfSpace& h : frustum_half_spaces(face.projection)) planes.push_back(h);
  const std::vector<dvec3> body = clipped_convex_hull(points, planes);
  std::vector<dvec3> body_ndc;
  for (const dvec3& q : body) {
    dvec3 n;
    if (face_ndc(face.projection, q, n)) body_ndc.push_back(n);
    s.body_bounds.extend(q);
  }
  if (body_ndc.empty()) return s;
  s.empty = false;
  // The view vector in the face's NDC, at the centre of B's bounds (stable under the duplicate
  // vertices clipping leaves).
  const dvec3 centre = s.body_bounds.center();
  const dvec3 forward = glm::normalize(camera.target - camera.position);
  dvec3 a, b;
  const double step = 1e-3 * diagonal;
  if (!face_ndc(face.projection, centre, a) ||
      !face_ndc(face.projection, centre + forward * step, b))
    return s;
  const dvec3 light_axis(0.0, 0.0, 1.0);
  dvec3 v = b - a;
  v -= light_axis * glm::dot(v, light_axis);
  if (glm::length(v) < 1e-9 * glm::length(b - a) || glm::length(b - a) == 0.0) return s;
  s.warped = true;
  s.y_axis = -light_axis;
  s.z_axis = glm::normalize(v);
  s.x_axis = glm::cross(s.y_axis, s.z_axis);
  Aabb ls;
  for (const dvec3& q : body_ndc)
    ls.extend(dvec3(glm::dot(q, s.x_axis), glm::dot(q, s.y_axis), glm::dot(q, s.z_axis)));
  const double depth = std::max(ls.hi.z - ls.lo.z, 1e-12);
  const double z_n = camera.near_plane;
  const double z_f = fit_far_plane(camera.position, forward, scene_bounds, z_n);
  s.n = depth * (z_n + std::sqrt(z_n * z_f)) / std::max(z_f - z_n, 1e-12);
  s.f = s.n + depth;
  dvec3 eye_ndc;
  const double eye_x = face_ndc(face.projection, camera.position, eye_ndc)
                           ? glm::dot(eye_ndc, s.x_axis)
                           : 0.5 * (ls.lo.x + ls.hi.x);
  s.eye = dvec3(eye_x, 0.5 * (ls.lo.y + ls.hi.y), ls.lo.z - s.n);
  s.u_lo = 1e300, s.u_hi = -1e300;
  for (const dvec3& q : body_ndc) {
    const dvec3 r =
        dvec3(glm::dot(q, s.x_axis), glm::dot(q, s.y_axis), glm::dot(q, s.z_axis)) - s.eye;
    const double u = r.x / std::clamp(r.z, s.n, s.f);
    s.u_lo = std::min(s.u_lo, u), s.u_hi = std::max(s.u_hi, u);
  }
  if (!(s.u_hi > s.u_lo)) s.u_hi = s.u_lo + 1e-12;
  return s;
}

bool LispsmSpace::box_rect(const Aabb& box, dvec2& lo, dvec2& hi) const {
  if (empty || box.empty()) return false;
  if (box.lo.x > body_bounds.hi.x || box.hi.x < body_bounds.lo.x || box.lo.y > body_bounds.hi.y ||
      box.hi.y < body_bounds.lo.y || box.lo.z > body_bounds.hi.z || box.hi.z < body_bounds.lo.z)
    return false;
  lo = dvec2(1e300), hi = dvec2(-1e300);
  for (int c = 0; c < 8; ++c) {
    const dvec3 corner((c & 1) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y,
                       (c & 4) ? box.hi.z : box.lo.z);
    dvec3 q;
    if (!face_ndc(face, corner, q)) {  // straddles the light's plane: all of the map
      lo = dvec2(-1.0), hi = dvec2(1.0);
      return true;
    }
    dvec2 m(q.x, q.y);
    if (warped) {
      const dvec3 r = dvec3(glm::dot(q, x_axis), glm::dot(q, y_axis), glm::dot(q, z_axis)) - eye;
      const double z = std::clamp(r.z, n, f);
      m = dvec2(2.0 * (r.x / z - u_lo) / (u_hi - u_lo) - 1.0,
                (f + n) / (f - n) - 2.0 * f * n / ((f - n) * z));
    }
    lo = glm::min(lo, m), hi = glm::max(hi, m);
  }
  lo = glm::max(lo, dvec2(-1.0)), hi = glm::min(hi, dvec2(1.0));
  return lo.x <= hi.x && lo.y <= hi.y;
}

}  // namespace dv
