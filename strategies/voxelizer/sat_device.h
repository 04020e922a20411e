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
// setup and the walk (SatWalk) pick axes, corners and edges by selects: every subscript is a
// constant and the test stays in registers.
//
// Work split (large triangles must not serialise on one thread; small ones, most triangles of a
// fine mesh, run all their work items on one thread with sat_all_work_items):
//   non-degenerate: one work item per voxel column of the bounding range seen along the
//     dominant normal axis a; the item checks the column against the projection along a, then
//     walks the few voxels along a that the plane can reach (at most about 5), stopping
//     after the run that passes.
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

// Picks by a run-time index through selects, never by subscript (see the header comment): x, y
// or z for `axis` 0, 1 or 2; component `axis` of v; the range of `axis`; an edge; a corner.
template <class T>
DV_HD inline T sat_pick(int axis, T x, T y, T z) {
  return axis == 0 ? x : (axis == 1 ? y : z);
}
DV_HD inline double sat_component(const dvec3& v, int axis) {
  return sat_pick(axis, v.x, v.y, v.z);
}
DV_HD inline VoxelRange sat_pick_range(int axis, const VoxelRange (&r)[3]) {
  VoxelRange picked;
  picked.first = sat_pick(axis, r[0].first, r[1].first, r[2].first);
  picked.last = sat_pick(axis, r[0].last, r[1].last, r[2].last);
  return picked;
}
DV_HD inline SatEdge sat_pick_edge(int axis, const SatEdge& x, const SatEdge& y, const SatEdge& z) {
  return SatEdge{sat_pick(axis, x.nu, y.nu, z.nu), sat_pick(axis, x.nv, y.nv, z.nv),
                 sat_pick(axis, x.d, y.d, z.d)};
}
DV_HD inline dvec3 sat_corner(const dvec3& v0, const dvec3& v1, const dvec3& v2, int index) {
  return dvec3(sat_pick(index, v0.x, v1.x, v2.x), sat_pick(index, v0.y, v1.y, v2.y),
               sat_pick(index, v0.z, v1.z, v2.z));
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
    t.work_items = int64_t(sat_pick_range((t.axis + 1) % 3, t.range).count()) *
                   sat_pick_range((t.axis + 2) % 3, t.range).count();
    return true;
  }
  // The segment a degenerate triangle collapses to: its longest edge (the third corner lies
  // within kDegenerateRatio * length of it, between its ends); the first of equal ones.
  const int longest =
      sat_first_largest(squared_length(v1 - v0), squared_length(v2 - v1), squared_length(v0 - v2));
  t.seg_p = sat_corner(v0, v1, v2, longest);
  t.seg_q = sat_corner(v0, v1, v2, (longest + 1) % 3);
  t.axis = sat_dominant_axis(t.seg_q - t.seg_p);
  t.work_items = sat_pick_range(t.axis, t.range).count();
  return true;
}

// The per-voxel decision (the voxel must lie in t.range; callers only enumerate those).
DV_HD inline bool sat_plane_passes(const dvec3& n, double d_min, double d_max, const ivec3& p) {
  const double np = n.x * double(p.x) + n.y * double(p.y) + n.z * double(p.z);
  return (np + d_min <= 0.0) & (np + d_max >= 0.0);
}
DV_HD inline bool sat_plane_passes(const SatTriangle& t, const ivec3& p) {
  return sat_plane_passes(t.n, t.d_min, t.d_max, p);
}

// One projection's three edges at box corner (pu, pv). The walk's per-voxel tests combine with &
// rather than && (here, in sat_plane_passes and sat_walk_side_tests_pass): each is a short chain
// of arithmetic, and evaluating all of them without a branch keeps the independent chains in
// flight together; the walk is bound by latency (results/perf/rounds/04-sat-walk).
DV_HD inline bool sat_edges_pass(const SatEdge (&e)[3], double pu, double pv) {
  return e[0].inside(pu, pv) & e[1].inside(pu, pv) & e[2].inside(pu, pv);
}

DV_HD inline bool sat_projection_passes(const SatTriangle& t, const ivec3& p, int a) {
  return sat_edges_pass(t.edges[a], double(p[(a + 1) % 3]), double(p[(a + 2) % 3]));
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

// A triangle's walk, its axes named for it: a = t.axis along the walk (a column, or across a
// degenerate triangle's slices), u = (a + 1) % 3 and w = (a + 2) % 3 across it. Picked once per
// triangle by selects, so one code path serves the three walk axes: a warp whose lanes walk
// along different axes runs one walk, not three one after another, and the walk needs nothing
// else. The tests read the numbers sat_voxel_passes reads, in the same order, so they decide the
// same.
struct SatWalk {
  int axis = 2;
  bool degenerate = false;
  SatEdge across[3];   // t.edges[a]: at corner (u, w)
  SatEdge along_u[3];  // t.edges[u]: at corner (w, a)
  SatEdge along_w[3];  // t.edges[w]: at corner (a, u)
  VoxelRange range_a, range_u, range_w;
  // Non-degenerate: the plane, and its components across the walk.
  dvec3 n{0.0};
  double d_min = 0.0, d_max = 0.0;
  double n_u = 0.0, n_w = 0.0, inv_n_a = 0.0;
  // Degenerate: the segment's start and direction, components (a, u, w).
  dvec3 seg_p{0.0}, seg_d{0.0};
};

DV_HD inline SatWalk sat_walk(const SatTriangle& t) {
  SatWalk c;
  const int a = t.axis, u = (a + 1) % 3, w = (a + 2) % 3;
  c.axis = a;
  c.degenerate = t.degenerate;
  for (int i = 0; i < 3; ++i) {
    c.across[i] = sat_pick_edge(a, t.edges[0][i], t.edges[1][i], t.edges[2][i]);
    c.along_u[i] = sat_pick_edge(u, t.edges[0][i], t.edges[1][i], t.edges[2][i]);
    c.along_w[i] = sat_pick_edge(w, t.edges[0][i], t.edges[1][i], t.edges[2][i]);
  }
  c.range_a = sat_pick_range(a, t.range);
  c.range_u = sat_pick_range(u, t.range);
  c.range_w = sat_pick_range(w, t.range);
  if (t.degenerate) {
    const dvec3 d = t.seg_q - t.seg_p;
    c.seg_p =
        dvec3(sat_component(t.seg_p, a), sat_component(t.seg_p, u), sat_component(t.seg_p, w));
    c.seg_d = dvec3(sat_component(d, a), sat_component(d, u), sat_component(d, w));
    return c;
  }
  c.n = t.n;
  c.d_min = t.d_min;
  c.d_max = t.d_max;
  c.n_u = sat_component(t.n, u);
  c.n_w = sat_component(t.n, w);
  c.inv_n_a = 1.0 / sat_component(t.n, a);  // the dominant component: not 0
  return c;
}

// The grid voxel at walk coordinate s and corner (pu, pw) across it.
DV_HD inline ivec3 sat_walk_voxel(const SatWalk& c, int s, int pu, int pw) {
  return ivec3(sat_pick(c.axis, s, pw, pu), sat_pick(c.axis, pu, s, pw),
               sat_pick(c.axis, pw, pu, s));
}

// The projections along u and w at voxel (s, pu, pw) (the one along a is the column's test).
DV_HD inline bool sat_walk_side_tests_pass(const SatWalk& c, int s, int pu, int pw) {
  return sat_edges_pass(c.along_u, double(pw), double(s)) &
         sat_edges_pass(c.along_w, double(s), double(pu));
}

// Non-degenerate: the column at (pu, pw). Where along it the plane test can pass is the
// interval between s1 and s2; [floor, ceil] of it holds every voxel the per-voxel test can
// pass (the rounding of s1, s2 and of the test is about 1e-13 voxel, and a voxel outside lies
// a whole voxel beyond), and the per-voxel test decides. Each test is monotone in the walk
// coordinate (a rounded product by a constant, then rounded sums with constants), so the
// voxels that pass are one run: the walk stops at the first failure after it.
DV_HD inline void sat_column(const SatWalk& c, int pu, int pw, const VoxelGridView& grid) {
  if (!sat_edges_pass(c.across, double(pu), double(pw))) return;
  const double base = c.n_u * double(pu) + c.n_w * double(pw);
  const double s1 = -(base + c.d_min) * c.inv_n_a, s2 = -(base + c.d_max) * c.inv_n_a;
  const int first = sat_clamp_index(::floor(min_value(s1, s2)), c.range_a.first, c.range_a.last);
  const int last = sat_clamp_index(::ceil(max_value(s1, s2)), c.range_a.first, c.range_a.last);
  // The set voxels' bits, gathered per grid word (a column along z fills words of 32).
  int64_t word = -1;
  uint32_t mask = 0;
  for (int s = first; s <= last; ++s) {
    const ivec3 p = sat_walk_voxel(c, s, pu, pw);
    if (!(sat_plane_passes(c.n, c.d_min, c.d_max, p) & sat_walk_side_tests_pass(c, s, pu, pw))) {
      if (mask) break;
      continue;
    }
    const int64_t index = grid.word_index(p.x, p.y, p.z >> 5);
    if (index != word) {
      grid.or_word(word, mask);
      word = index;
      mask = 0;
    }
    mask |= 1u << (p.z & 31);
  }
  grid.or_word(word, mask);
}

// The range of voxels across the walk that the segment's part between parameters lam_lo and
// lam_hi can touch, widened by a voxel (rounding, and the third corner of a sliver); p and d
// are the segment's start and direction along that axis, `range` the triangle's range there.
DV_HD inline VoxelRange sat_segment_window(double p, double d, double lam_lo, double lam_hi,
                                           const VoxelRange& range) {
  const double c0 = p + lam_lo * d, c1 = p + lam_hi * d;
  VoxelRange r = voxel_range(min_value(c0, c1), max_value(c0, c1), range.last + 1, 1.0);
  r.first = max_value(r.first, range.first);
  r.last = min_value(r.last, range.last);
  return r;
}

// Degenerate: the slice at walk coordinate s, across the segment's dominant axis.
DV_HD inline void sat_segment_slice(const SatWalk& c, int s, const VoxelGridView& grid) {
  double lam_lo = 0.0, lam_hi = 1.0;
  if (c.seg_d.x != 0.0) {
    const double l0 = (double(s) - c.seg_p.x) / c.seg_d.x;
    const double l1 = (double(s + 1) - c.seg_p.x) / c.seg_d.x;
    lam_lo = clamp_value(min_value(l0, l1), 0.0, 1.0);
    lam_hi = clamp_value(max_value(l0, l1), 0.0, 1.0);
  }
  const VoxelRange window_u = sat_segment_window(c.seg_p.y, c.seg_d.y, lam_lo, lam_hi, c.range_u);
  const VoxelRange window_w = sat_segment_window(c.seg_p.z, c.seg_d.z, lam_lo, lam_hi, c.range_w);
  for (int pw = window_w.first; pw <= window_w.last; ++pw)
    for (int pu = window_u.first; pu <= window_u.last; ++pu)
      if (sat_edges_pass(c.across, double(pu), double(pw)) &&
          sat_walk_side_tests_pass(c, s, pu, pw)) {
        const ivec3 p = sat_walk_voxel(c, s, pu, pw);
        grid.set(p.x, p.y, p.z);
      }
}

// Work item `local` of a triangle: a slice of a degenerate one, else a column of the range
// across its walk axis, rows along u.
DV_HD inline void sat_work_item(const SatWalk& c, int64_t local, const VoxelGridView& grid) {
  if (c.degenerate) return sat_segment_slice(c, c.range_a.first + int(local), grid);
  const int64_t count_u = c.range_u.count();
  sat_column(c, c.range_u.first + int(local % count_u), c.range_w.first + int(local / count_u),
             grid);
}

// Every work item of a triangle on the calling thread (the small triangles' route): the same
// voxels as sat_work_item for every item, without the per-item index arithmetic. One loop over
// the columns, not a loop over rows of columns: a warp's lanes walk triangles of different
// shapes, and nested loops would make the warp run its most rows times its longest row.
DV_HD inline void sat_all_work_items(const SatWalk& c, const VoxelGridView& grid) {
  if (c.degenerate) {
    for (int s = c.range_a.first; s <= c.range_a.last; ++s) sat_segment_slice(c, s, grid);
    return;
  }
  const int64_t columns = int64_t(c.range_u.count()) * c.range_w.count();
  int pu = c.range_u.first, pw = c.range_w.first;
  for (int64_t k = 0; k < columns; ++k) {
    sat_column(c, pu, pw, grid);
    if (++pu > c.range_u.last) {
      pu = c.range_u.first;
      ++pw;
    }
  }
}

}  // namespace dv
