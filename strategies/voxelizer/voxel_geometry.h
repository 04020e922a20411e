// Geometry both conservative voxelizers share, in grid coordinates (voxel (i, j, k) is the
// closed unit cube [i, i+1] x [j, j+1] x [k, k+1]): the triangle normal, the one rule that
// calls a triangle degenerate, and the range of voxels a closed interval touches. exact and sat
// use these same functions so that they agree on which triangles have a usable normal. The
// point methods (slicemap, atlas) share the half-open cell rule for points at the end.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/hd.h"
#include "core/math.h"

namespace dv {

// A triangle is degenerate (a segment or a point) when its height over its longest edge is at
// most this: |n| <= kDegenerateRatio * longest^2, n = (v1 - v0) x (v2 - v1). Above it the
// rounded normal's direction is good to about 2e-16 / kDegenerateRatio radians, so the plane
// test it drives errs by under 1e-5 voxel across a 10^4-voxel triangle; below it the plane
// axis is skipped, which can only add voxels, and only within kDegenerateRatio * length of the
// triangle.
inline constexpr double kDegenerateRatio = 1e-7;

// Component a of (v1 - v0) x (v2 - v1): twice the signed area of the triangle projected along
// axis a onto coordinates (u, v) = ((a+1) % 3, (a+2) % 3), i.e. (y,z), (z,x), (x,y). Note the
// (z, x) order for a = 1: projected with (x, z) coordinates the orientation would be -n.y.
DV_HD inline double triangle_area2(const dvec3& v0, const dvec3& v1, const dvec3& v2, int a) {
  const int u = (a + 1) % 3, v = (a + 2) % 3;
  const double e0u = v1[u] - v0[u], e0v = v1[v] - v0[v];
  const double e1u = v2[u] - v1[u], e1v = v2[v] - v1[v];
  return e0u * e1v - e0v * e1u;
}

DV_HD inline dvec3 triangle_normal(const dvec3& v0, const dvec3& v1, const dvec3& v2) {
  return dvec3(triangle_area2(v0, v1, v2, 0), triangle_area2(v0, v1, v2, 1),
               triangle_area2(v0, v1, v2, 2));
}

DV_HD inline double squared_length(const dvec3& d) {
  return d.x * d.x + d.y * d.y + d.z * d.z;
}

// Both sides of the comparison are fourth powers of the coordinates, which overflow beyond
// about 1e77 grid units; a triangle that long first has n and longest^2 scaled by 2^-400, a
// power of two, so the comparison is the unscaled one (exact below, finite above).
DV_HD inline bool is_degenerate_triangle(const dvec3& v0, const dvec3& v1, const dvec3& v2,
                                         const dvec3& n) {
  double longest2 = max_value(squared_length(v1 - v0),
                              max_value(squared_length(v2 - v1), squared_length(v0 - v2)));
  const double scale = longest2 > 0x1p400 ? 0x1p-400 : 1.0;
  longest2 *= scale;
  const double limit = kDegenerateRatio * longest2;
  return squared_length(n * scale) <= limit * limit;
}

// Grid coordinates the tests accept: every product they form stays finite. The largest is the
// plane offset n . (c - v), a sum of three terms of at most 2 (2 big)^2 (big + 1) = 8e300 for
// big = 1e100 (n's components are cross products of edges up to 2 big long); edge tests form
// products of two coordinates. NaN fails every comparison, so it is rejected too.
DV_HD inline bool is_finite_point(const dvec3& p) {
  const double big = 1.0e100;
  return p.x == p.x && p.y == p.y && p.z == p.z && p.x > -big && p.x < big && p.y > -big &&
         p.y < big && p.z > -big && p.z < big;
}

// Voxels [first, last] whose closed boxes meet the closed interval [lo - grow, hi + grow] on
// an axis of `res` voxels; empty (first > last) when it misses the grid.
struct VoxelRange {
  int first = 0, last = -1;
  DV_HD bool empty() const { return first > last; }
  DV_HD int count() const { return empty() ? 0 : last - first + 1; }
};

DV_HD inline VoxelRange voxel_range(double lo, double hi, int res, double grow) {
  VoxelRange r;
  if (!(lo <= hi)) return r;  // also rejects NaN
  const double first = clamp_value(::ceil(lo - grow) - 1.0, -1.0, double(res));
  const double last = clamp_value(::floor(hi + grow), -1.0, double(res));
  r.first = max_value(int(first), 0);
  r.last = min_value(int(last), res - 1);
  return r;
}

// The voxel along an axis of `res` voxels holding grid coordinate g for the point methods
// (slicemap, atlas): the half-open cell [k, k+1) with k = floor(g), and the last voxel for g ==
// res exactly (the grid's closed upper face, voxel_grid.h); -1 outside [0, res] or for NaN.
DV_HD inline int point_voxel(double g, int res) {
  if (!(g >= 0.0 && g <= double(res))) return -1;
  return min_value(int(g), res - 1);
}

// The voxel holding grid-space point g (each axis as point_voxel); false when g lies outside
// the grid's closed box.
DV_HD inline bool point_voxel_index(const dvec3& g, const ivec3& res, ivec3& out) {
  out = ivec3(point_voxel(g.x, res.x), point_voxel(g.y, res.y), point_voxel(g.z, res.z));
  return out.x >= 0 && out.y >= 0 && out.z >= 0;
}

}  // namespace dv
