// Shared CPU/CUDA code of the `sat` voxelizer: the triangle/box overlap test of Schwarz & Seidel
// (2010, §3.1; Buchacher 2014 §3.3) in grid coordinates, where voxel p is the closed box
// [p, p+1]. A voxel is set when it lies in the triangle's voxel bounding range, the triangle's
// plane passes through the box (critical-point test) and the box meets the triangle's
// projection along each axis (three 2D edge-function tests with the critical-corner offsets).
// For a degenerate triangle (voxel_geometry.h: no usable normal) the plane test is skipped and
// the bounding range and the three projections decide: exactly the separating axes of the
// segment or point it collapses to, so the result stays conservative.
//
// Everything is double precision in a fixed evaluation order and the build forbids FMA
// contraction, so the CPU and CUDA grids are identical. The result is the set of voxels that
// pass sat_voxel_passes(); the work split below only enumerates candidate supersets of it.
//
// Registers, not local memory: on the device a SatTriangle subscripted by a run-time axis or
// corner index lives in the thread's stack (440 bytes, every edge test a local load). So the
// setup picks axes and corners by selects, and the walks are templates on the walk axis,
// reached through one switch (sat_work_item, sat_all_work_items): inside, every subscript is a
// constant and the test stays in registers.
//
// Work split (large triangles must not serialise on one thread; small ones, most triangles of a
// fine mesh, run all their work items on one thread with sat_all_work_items):
//   non-degenerate: one work item per voxel column of the bounding range seen along the
//     dominant normal axis a; the item checks the column against the projection along a, then
//     walks the few voxels along a that the plane can reach (at most about 7).
//   degenerate: one work item per slice of the bounding range across the segment's dominant
//     axis; the item tests the small window (at most 4 x 4 voxels) the segment crosses there.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "core/math.h"
#include "strategies/voxelizer/voxel_geometry.h"
#include "strategies/voxelizer/voxel_grid.h"

namespace dv {

// Edge function of one projected edge: the box with min corner (pu, pv) meets the edge's inner
// half-plane when nu * pu + nv * pv + d >= 0 (d holds the critical-corner offset).
struct SatEdge {
  double nu = 0.0, nv = 0.0, d = 0.0;
  DV_HD bool inside(double pu, double pv) const { return nu * pu + nv * pv + d >= 0.0; }
};

struct SatTriangle {
  dvec3 v[3];
  dvec3 n;  // (v1 - v0) x (v2 - v1)
  bool degenerate = false;
  double d_min = 0.0, d_max = 0.0;  // n.p + d_min / d_max: the plane at the box's low / high corner
  SatEdge edges[3][3];              // [projection axis a][edge]; coordinates ((a+1)%3, (a+2)%3)
  VoxelRange range[3];              // voxel bounding range per axis
  int axis = 2;                     // axis a work item walks along (see the header comment)
  dvec3 seg_p{0.0}, seg_q{0.0};     // degenerate: the segment's ends (longest edge)
  int64_t work_items = 0;
};

// 0, 1 or 2: which of a, b, c is largest, the first of equal ones.
DV_HD inline int sat_first_largest(double a, double b, double c) {
  int index = 0;
  double most = a;
  if (b > most) {
    index = 1;
    most = b;
  }
  if (c > most) index = 2;
  return index;
}

// The axis along which d is longest; ties go to z, then y.
DV_HD inline int sat_dominant_axis(const dvec3& d) {
  return 2 - sat_first_largest(d.z * d.z, d.y * d.y, d.x * d.x);
}

// The range count of `axis`, or corner v0 / v1 / v2 by `index`, through selects (see the
// header comment).
DV_HD inline int64_t sat_range_count(const VoxelRange (&range)[3], int axis) {
  const int64_t x = range[0].count(), y = range[1].count(), z = range[2].count();
  return axis == 0 ? x : (axis == 1 ? y : z);
}
DV_HD inline dvec3 sat_corner(const dvec3& v0, const dvec3& v1, const dvec3& v2, int index) {
  return dvec3(index == 0 ? v0.x : (index == 1 ? v1.x : v2.x),
               index == 0 ? v0.y : (index == 1 ? v1.y : v2.y),
               index == 0 ? v0.z : (index == 1 ? v1.z : v2.z));
}

// Builds the test for triangle (v0, v1, v2) in grid coordinates of a `res` grid; false when it
// misses the grid (or has a non-finite corner), in which case it has no work items.
DV_HD inline bool sat_setup(const dvec3& v0, const dvec3& v1, const dvec3& v2, const ivec3& res,
                            SatTriangle& t) {
  t.work_items = 0;
  if (!is_finite_point(v0) || !is_finite_point(v1) || !is_finite_point(v2)) return false;
  t.v[0] = v0;
  t.v[1] = v1;
  t.v[2] = v2;
  for (int a = 0; a < 3; ++a) {
    t.range[a] = voxel_range(min_value(v0[a], min_value(v1[a], v2[a])),
                             max_value(v0[a], max_value(v1[a], v2[a])), res[a], 0.0);
    if (t.range[a].empty()) return false;
  }
  t.n = triangle_normal(v0, v1, v2);
  t.degenerate = is_degenerate_triangle(v0, v1, v2, t.n);

  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, w = (a + 2) % 3;
    const double s = t.n[a] >= 0.0 ? 1.0 : -1.0;  // orientation of the (u, w) projection
    for (int i = 0; i < 3; ++i) {
      const dvec3& p = t.v[i];
      const dvec3& q = t.v[(i + 1) % 3];
      SatEdge& e = t.edges[a][i];
      e.nu = -(q[w] - p[w]) * s;
      e.nv = (q[u] - p[u]) * s;
      e.d = -(e.nu * p[u] + e.nv * p[w]) + max_value(0.0, e.nu) + max_value(0.0, e.nv);
    }
  }

  const dvec3 c(t.n.x > 0.0 ? 1.0 : 0.0, t.n.y > 0.0 ? 1.0 : 0.0, t.n.z > 0.0 ? 1.0 : 0.0);
  t.d_max = t.n.x * (c.x - v0.x) + t.n.y * (c.y - v0.y) + t.n.z * (c.z - v0.z);
  t.d_min =
      t.n.x * ((1.0 - c.x) - v0.x) + t.n.y * ((1.0 - c.y) - v0.y) + t.n.z * ((1.0 - c.z) - v0.z);

  if (!t.degenerate) {
    t.axis = sat_dominant_axis(t.n);
    t.work_items =
        sat_range_count(t.range, (t.axis + 1) % 3) * sat_range_count(t.range, (t.axis + 2) % 3);
    return true;
  }
  // The segment a degenerate triangle collapses to: its longest edge (the third corner lies
  // within kDegenerateRatio * length of it, between its ends); the first of equal ones.
  const int longest =
      sat_first_largest(squared_length(v1 - v0), squared_length(v2 - v1), squared_length(v0 - v2));
  t.seg_p = sat_corner(v0, v1, v2, longest);
  t.seg_q = sat_corner(v0, v1, v2, (longest + 1) % 3);
  t.axis = sat_dominant_axis(t.seg_q - t.seg_p);
  t.work_items = sat_range_count(t.range, t.axis);
  return true;
}

// The per-voxel decision (the voxel must lie in t.range; callers only enumerate those).
DV_HD inline bool sat_plane_passes(const SatTriangle& t, const ivec3& p) {
  const double np = t.n.x * double(p.x) + t.n.y * double(p.y) + t.n.z * double(p.z);
  return np + t.d_min <= 0.0 && np + t.d_max >= 0.0;
}

DV_HD inline bool sat_projection_passes(const SatTriangle& t, const ivec3& p, int a) {
  const double pu = double(p[(a + 1) % 3]), pv = double(p[(a + 2) % 3]);
  return t.edges[a][0].inside(pu, pv) && t.edges[a][1].inside(pu, pv) &&
         t.edges[a][2].inside(pu, pv);
}

DV_HD inline bool sat_voxel_passes(const SatTriangle& t, const ivec3& p) {
  if (!t.degenerate && !sat_plane_passes(t, p)) return false;
  return sat_projection_passes(t, p, 0) && sat_projection_passes(t, p, 1) &&
         sat_projection_passes(t, p, 2);
}

// Clamps a double to [lo, hi] before turning it into an int (no overflow, no NaN).
DV_HD inline int sat_clamp_index(double x, int lo, int hi) {
  if (!(x >= double(lo))) return lo;
  if (x > double(hi)) return hi;
  return int(x);
}

// Non-degenerate: the column along A = t.axis at p[(A+1)%3] = pu, p[(A+2)%3] = pw.
template <int A>
DV_HD inline void sat_column_at(const SatTriangle& t, int pu, int pw, const VoxelGridView& grid) {
  constexpr int u = (A + 1) % 3, w = (A + 2) % 3;
  ivec3 p;
  p[u] = pu;
  p[w] = pw;
  if (!sat_projection_passes(t, p, A)) return;
  // Where along the column the plane test can pass, widened by a voxel for rounding; the
  // per-voxel test below decides.
  const double base = t.n[u] * double(p[u]) + t.n[w] * double(p[w]);
  const double t1 = -(base + t.d_min) / t.n[A], t2 = -(base + t.d_max) / t.n[A];
  const int first =
      sat_clamp_index(::floor(min_value(t1, t2)) - 1.0, t.range[A].first, t.range[A].last);
  const int last =
      sat_clamp_index(::ceil(max_value(t1, t2)) + 1.0, t.range[A].first, t.range[A].last);
  if constexpr (A == 2) {
    // Walking z: collect the bits of each 32-slice word and OR them in once.
    int word = first >> 5;
    uint32_t mask = 0;
    for (p.z = first; p.z <= last; ++p.z) {
      if ((p.z >> 5) != word) {
        grid.set_bits(p.x, p.y, word, mask);
        word = p.z >> 5;
        mask = 0;
      }
      if (sat_plane_passes(t, p) && sat_projection_passes(t, p, u) &&
          sat_projection_passes(t, p, w))
        mask |= 1u << (p.z & 31);
    }
    grid.set_bits(p.x, p.y, word, mask);
  } else {
    for (p[A] = first; p[A] <= last; ++p[A])
      if (sat_plane_passes(t, p) && sat_projection_passes(t, p, u) &&
          sat_projection_passes(t, p, w))
        grid.set(p.x, p.y, p.z);
  }
}

// The range of voxels along axis b that the segment's part between parameters lam_lo and
// lam_hi can touch, widened by a voxel (rounding, and the third corner of a sliver).
template <int B>
DV_HD inline VoxelRange sat_segment_window(const SatTriangle& t, const dvec3& d, double lam_lo,
                                           double lam_hi) {
  const double c0 = t.seg_p[B] + lam_lo * d[B], c1 = t.seg_p[B] + lam_hi * d[B];
  VoxelRange r = voxel_range(min_value(c0, c1), max_value(c0, c1), t.range[B].last + 1, 1.0);
  r.first = max_value(r.first, t.range[B].first);
  r.last = min_value(r.last, t.range[B].last);
  return r;
}

// Degenerate work item `local`: one slice across the segment's dominant axis A = t.axis.
template <int A>
DV_HD inline void sat_segment_slice(const SatTriangle& t, int64_t local,
                                    const VoxelGridView& grid) {
  constexpr int u = (A + 1) % 3, w = (A + 2) % 3;
  const int slice = t.range[A].first + int(local);
  const dvec3 d = t.seg_q - t.seg_p;
  double lam_lo = 0.0, lam_hi = 1.0;
  if (d[A] != 0.0) {
    const double l0 = (double(slice) - t.seg_p[A]) / d[A];
    const double l1 = (double(slice + 1) - t.seg_p[A]) / d[A];
    lam_lo = clamp_value(min_value(l0, l1), 0.0, 1.0);
    lam_hi = clamp_value(max_value(l0, l1), 0.0, 1.0);
  }
  const VoxelRange window_u = sat_segment_window<u>(t, d, lam_lo, lam_hi);
  const VoxelRange window_w = sat_segment_window<w>(t, d, lam_lo, lam_hi);
  ivec3 p;
  p[A] = slice;
  for (p[w] = window_w.first; p[w] <= window_w.last; ++p[w])
    for (p[u] = window_u.first; p[u] <= window_u.last; ++p[u])
      if (sat_voxel_passes(t, p)) grid.set(p.x, p.y, p.z);
}

// Work item `local` of a triangle walking along A: a slice of a degenerate one, else a column
// of the range across A, rows along (A+1)%3.
template <int A>
DV_HD inline void sat_work_item_along(const SatTriangle& t, int64_t local,
                                      const VoxelGridView& grid) {
  if (t.degenerate) return sat_segment_slice<A>(t, local, grid);
  constexpr int u = (A + 1) % 3, w = (A + 2) % 3;
  const int64_t count_u = t.range[u].count();
  sat_column_at<A>(t, t.range[u].first + int(local % count_u),
                   t.range[w].first + int(local / count_u), grid);
}

DV_HD inline void sat_work_item(const SatTriangle& t, int64_t local, const VoxelGridView& grid) {
  switch (t.axis) {
    case 0:
      return sat_work_item_along<0>(t, local, grid);
    case 1:
      return sat_work_item_along<1>(t, local, grid);
    default:
      return sat_work_item_along<2>(t, local, grid);
  }
}

// Every work item of `t` on the calling thread (the small triangles' route): the same voxels as
// sat_work_item for local = 0 .. t.work_items - 1, without the per-item index arithmetic.
template <int A>
DV_HD inline void sat_all_work_items_along(const SatTriangle& t, const VoxelGridView& grid) {
  if (t.degenerate) {
    for (int64_t local = 0; local < t.work_items; ++local) sat_segment_slice<A>(t, local, grid);
    return;
  }
  constexpr int u = (A + 1) % 3, w = (A + 2) % 3;
  for (int pw = t.range[w].first; pw <= t.range[w].last; ++pw)
    for (int pu = t.range[u].first; pu <= t.range[u].last; ++pu) sat_column_at<A>(t, pu, pw, grid);
}

DV_HD inline void sat_all_work_items(const SatTriangle& t, const VoxelGridView& grid) {
  switch (t.axis) {
    case 0:
      return sat_all_work_items_along<0>(t, grid);
    case 1:
      return sat_all_work_items_along<1>(t, grid);
    default:
      return sat_all_work_items_along<2>(t, grid);
  }
}

}  // namespace dv
