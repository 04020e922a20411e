// Ray queries over the scene's BVH, shared by host and device: a watertight ray/triangle test
// (Woop, Benthin & Wald 2013) in double precision with a top-left tie rule, so a ray through a
// shared edge or vertex of a closed mesh crosses it exactly once; and traversals that visit
// every hit on a segment or find the next hit after a given one.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "core/math.h"
#include "engine/scene/scene_view.h"

namespace dv {

struct RayHit {
  double t;           // distance along the unit direction
  uint32_t triangle;  // BVH-order index
  bool entering;      // the ray passes from the outside (normal side) to the inside
};

// Precomputed per-ray shear (Woop et al.): the ray becomes the +z axis.
struct ShearedRay {
  dvec3 origin;
  dvec3 dir;
  dvec3 inv_dir;
  int kx, ky, kz;
  double sx, sy, sz;
};

DV_HD inline ShearedRay make_sheared_ray(const dvec3& origin, const dvec3& dir) {
  ShearedRay r;
  r.origin = origin;
  r.dir = dir;
  r.inv_dir = dvec3(1.0 / dir.x, 1.0 / dir.y, 1.0 / dir.z);
  dvec3 a = glm::abs(dir);
  r.kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  r.kx = (r.kz + 1) % 3;
  r.ky = (r.kx + 1) % 3;
  if (dir[r.kz] < 0.0) {
    int tmp = r.kx;
    r.kx = r.ky;
    r.ky = tmp;
  }
  r.sx = dir[r.kx] / dir[r.kz];
  r.sy = dir[r.ky] / dir[r.kz];
  r.sz = 1.0 / dir[r.kz];
  return r;
}

// Top-left rule for an edge of zero edge-function value: the edge (dx, dy) in the sheared plane,
// oriented so the triangle's inside is on its positive side, owns the points on it when it is a
// "top" or "left" edge. Two triangles sharing the edge see it with opposite directions, so
// exactly one of them owns it.
DV_HD inline bool owns_edge(double dx, double dy) {
  return dy > 0.0 || (dy == 0.0 && dx < 0.0);
}

// Intersects the ray with triangle (p0, p1, p2). On a hit writes t and whether the ray enters
// (the triangle's counter-clockwise normal faces against the ray).
DV_HD inline bool intersect_triangle(const ShearedRay& r, const dvec3& p0, const dvec3& p1,
                                     const dvec3& p2, double& t_out, bool& entering) {
  const dvec3 a = p0 - r.origin, b = p1 - r.origin, c = p2 - r.origin;
  const double ax = a[r.kx] - r.sx * a[r.kz], ay = a[r.ky] - r.sy * a[r.kz];
  const double bx = b[r.kx] - r.sx * b[r.kz], by = b[r.ky] - r.sy * b[r.kz];
  const double cx = c[r.kx] - r.sx * c[r.kz], cy = c[r.ky] - r.sy * c[r.kz];
  double u = cx * by - cy * bx;  // edge p1 -> p2
  double v = ax * cy - ay * cx;  // edge p2 -> p0
  double w = bx * ay - by * ax;  // edge p0 -> p1
  if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return false;
  const double det = u + v + w;
  if (det == 0.0) return false;
  if (u == 0.0 || v == 0.0 || w == 0.0) {
    const double s = det > 0.0 ? 1.0 : -1.0;  // orient edges so the inside is positive
    if (u == 0.0 && !owns_edge(s * (cx - bx), s * (cy - by))) return false;
    if (v == 0.0 && !owns_edge(s * (ax - cx), s * (ay - cy))) return false;
    if (w == 0.0 && !owns_edge(s * (bx - ax), s * (by - ay))) return false;
  }
  const double az = r.sz * a[r.kz], bz = r.sz * b[r.kz], cz = r.sz * c[r.kz];
  t_out = (u * az + v * bz + w * cz) / det;
  // det > 0 means p0, p1, p2 run counter-clockwise seen from the ray origin looking along the
  // ray, i.e. the normal (p1-p0)x(p2-p0) points back toward the origin: the ray enters.
  entering = det > 0.0;
  return true;
}

// Where the ray meets the plane of a triangle the rasterizer found under a pixel: the exact depth
// of that fragment (no inside test: coverage was decided in fixed point). False when the ray
// runs parallel to the plane; `entering` as for intersect_triangle.
DV_HD inline bool triangle_plane_hit(const SceneView& s, uint32_t tri, const dvec3& origin,
                                     const dvec3& dir, double& t, bool& entering) {
  const u32vec3 idx = s.triangles[tri];
  const dvec3 p0 = s.vertices[idx.x];
  const dvec3 n = glm::cross(s.vertices[idx.y] - p0, s.vertices[idx.z] - p0);
  const double facing = glm::dot(n, dir);
  if (facing == 0.0) return false;
  t = glm::dot(n, p0 - origin) / facing;
  entering = facing < 0.0;
  return true;
}

// The point of triangle (a, b, c) nearest to p, for p in its plane (Ericson 2005, §5.1.5); p
// itself when it lies inside. A rasterized fragment's plane point can lie outside its triangle
// by the coverage test's fixed-point rounding, where the plane's extension passes behind (or in
// front of) the neighbouring triangle; moved onto the triangle it is a point of the surface.
DV_HD inline dvec3 nearest_point_on_triangle(const dvec3& p, const dvec3& a, const dvec3& b,
                                             const dvec3& c) {
  const dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + ab * (d1 / (d1 - d3));
  const dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  return p;
}

// Slab test of the ray origin + t dir (inv_dir its componentwise inverse) against a box:
// narrows [t_min, t_max] to the part inside the box; false when nothing of it is.
DV_HD inline bool clip_ray_to_box(const dvec3& origin, const dvec3& dir, const dvec3& inv_dir,
                                  const Aabb& box, double& t_min, double& t_max) {
  for (int axis = 0; axis < 3; ++axis) {
    if (dir[axis] == 0.0) {
      if (origin[axis] < box.lo[axis] || origin[axis] > box.hi[axis]) return false;
      continue;
    }
    double t0 = (box.lo[axis] - origin[axis]) * inv_dir[axis];
    double t1 = (box.hi[axis] - origin[axis]) * inv_dir[axis];
    if (t0 > t1) {
      double tmp = t0;
      t0 = t1;
      t1 = tmp;
    }
    // Conservative: never lose a hit on the box surface to rounding.
    t0 -= 1e-12 * (t0 < 0.0 ? -t0 : t0);
    t1 += 1e-12 * (t1 < 0.0 ? -t1 : t1);
    t_min = t0 > t_min ? t0 : t_min;
    t_max = t1 < t_max ? t1 : t_max;
    if (t_min > t_max) return false;
  }
  return true;
}

// Slab test of the ray against a box for t in [t_min, t_max].
DV_HD inline bool ray_hits_box(const ShearedRay& r, const Aabb& box, double t_min, double t_max) {
  return clip_ray_to_box(r.origin, r.dir, r.inv_dir, box, t_min, t_max);
}

DV_HD inline bool intersect_scene_triangle(const SceneView& s, const ShearedRay& r, uint32_t tri,
                                           double& t, bool& entering) {
  const u32vec3 idx = s.triangles[tri];
  return intersect_triangle(r, s.vertices[idx.x], s.vertices[idx.y], s.vertices[idx.z], t,
                            entering);
}

// Depth-first BVH traversal: calls on_hit(const RayHit&) for every triangle hit inside a node
// whose box the ray meets within [t_min, t_max]; on_hit may lower t_max (closest-hit queries)
// and returns false to stop.
template <class OnHit>
DV_HD void traverse_bvh(const SceneView& s, const ShearedRay& r, double t_min, double& t_max,
                        OnHit&& on_hit) {
  if (s.nodes.size == 0) return;
  int32_t stack[kBvhMaxDepth + 2];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int32_t index = stack[--top];
    const BvhNode& node = s.nodes[index];
    if (!ray_hits_box(r, node.box, t_min, t_max)) continue;
    if (node.count > 0) {
      for (int32_t i = node.first; i < node.first + node.count; ++i) {
        double t;
        bool entering;
        if (intersect_scene_triangle(s, r, uint32_t(i), t, entering) &&
            !on_hit(RayHit{t, uint32_t(i), entering}))
          return;
      }
    } else {
      stack[top++] = node.first;  // right child
      stack[top++] = index + 1;   // left child, visited first
    }
  }
}

// Calls visit(const RayHit&) for every hit with t in (t_min, t_max], in no particular order.
// visit returns false to stop early.
template <class Visit>
DV_HD void for_each_hit(const SceneView& s, const ShearedRay& r, double t_min, double t_max,
                        Visit&& visit) {
  traverse_bvh(s, r, t_min, t_max,
               [&](const RayHit& h) { return !(h.t > t_min && h.t <= t_max) || visit(h); });
}

// The first hit strictly after (t_after, after_triangle) in (t, triangle) order, with t <= t_max:
// walking a ray hit by hit with this visits coincident surfaces one at a time, each once.
DV_HD inline bool next_hit(const SceneView& s, const ShearedRay& r, double t_after,
                           int64_t after_triangle, double t_max, RayHit& out) {
  bool found = false;
  double limit = t_max;
  const double box_min = t_after - 1e-12 * (t_after < 0.0 ? -t_after : t_after) - 1e-300;
  traverse_bvh(s, r, box_min, limit, [&](const RayHit& h) {
    const bool after = h.t > t_after || (h.t == t_after && int64_t(h.triangle) > after_triangle);
    if (after && h.t <= limit &&
        (!found || h.t < out.t || (h.t == out.t && h.triangle < out.triangle))) {
      out = h;
      found = true;
      limit = h.t;
    }
    return true;
  });
  return found;
}

}  // namespace dv
