// Sampling of density volumes for host and device: trilinear interpolation of vertex-centred
// samples (clamped at the edges), the piecewise-linear transfer function, and the density
// gradient used as the shading normal. Shared by the oracle and every renderer.
#pragma once

#include "core/hd.h"
#include "core/math.h"
#include "engine/scene/ray_query.h"
#include "engine/scene/scene_view.h"

namespace dv {

DV_HD inline dvec3 world_to_grid(const ObjectView& o, const dvec3& world) {
  return dvec3(o.world_to_grid * dvec4(world, 1.0));
}

DV_HD inline double sample_at(const SceneView& s, const VolumeView& v, int x, int y, int z) {
  return double(s.densities[v.offset + (int64_t(z) * v.dims.y + y) * v.dims.x + x]);
}

// The cell of a volume around continuous grid coordinates g (sample i sits at g = i): its eight
// corner samples (bit 0: +x, bit 1: +y, bit 2: +z), the fractions inside it, and which axes
// were not clamped (outside the grid the density is constant along a clamped axis).
struct GridCell {
  double corner[8];
  double f[3];
  bool varies[3];
};

// The cell holding continuous grid coordinates g, clamped into the grid: its low corner sample
// per axis (0 on an axis of one sample).
DV_HD inline void cell_of_grid_point(const VolumeView& v, const dvec3& g, int cell[3]) {
  for (int a = 0; a < 3; ++a) {
    const double c = clamp_value(g[a], 0.0, double(v.dims[a] - 1));
    int i = int(c);  // c >= 0, so truncation is floor
    if (i > v.dims[a] - 2) i = v.dims[a] - 2 < 0 ? 0 : v.dims[a] - 2;
    cell[a] = i;
  }
}

// The eight samples around a cell (bit 0: +x, bit 1: +y, bit 2: +z; on an axis of one sample
// both sides are that sample).
DV_HD inline void cell_corners(const SceneView& s, const VolumeView& v, const int cell[3],
                               double corner[8]) {
  int i1[3];
  for (int a = 0; a < 3; ++a) i1[a] = v.dims[a] > 1 ? cell[a] + 1 : cell[a];
  for (int k = 0; k < 8; ++k)
    corner[k] =
        sample_at(s, v, k & 1 ? i1[0] : cell[0], k & 2 ? i1[1] : cell[1], k & 4 ? i1[2] : cell[2]);
}

DV_HD inline GridCell grid_cell(const SceneView& s, const VolumeView& v, const dvec3& g) {
  GridCell cell;
  int i0[3];
  cell_of_grid_point(v, g, i0);
  for (int a = 0; a < 3; ++a) {
    const double hi = double(v.dims[a] - 1);
    cell.f[a] = v.dims[a] > 1 ? clamp_value(g[a], 0.0, hi) - double(i0[a]) : 0.0;
    cell.varies[a] = v.dims[a] > 1 && g[a] >= 0.0 && g[a] <= hi;
  }
  cell_corners(s, v, i0, cell.corner);
  return cell;
}

DV_HD inline double trilinear(const GridCell& c) {
  const double* v = c.corner;
  const double c00 = v[0] * (1 - c.f[0]) + v[1] * c.f[0];
  const double c10 = v[2] * (1 - c.f[0]) + v[3] * c.f[0];
  const double c01 = v[4] * (1 - c.f[0]) + v[5] * c.f[0];
  const double c11 = v[6] * (1 - c.f[0]) + v[7] * c.f[0];
  const double c0 = c00 * (1 - c.f[1]) + c10 * c.f[1];
  const double c1 = c01 * (1 - c.f[1]) + c11 * c.f[1];
  return c0 * (1 - c.f[2]) + c1 * c.f[2];
}

// The exact derivative of the trilinear interpolant inside the cell, per grid unit.
DV_HD inline dvec3 trilinear_gradient(const GridCell& c) {
  dvec3 grad(0.0);
  for (int a = 0; a < 3; ++a) {
    if (!c.varies[a]) continue;
    const int b = (a + 1) % 3, d = (a + 2) % 3;  // the other two axes
    for (int k = 0; k < 8; ++k) {
      if (k & (1 << a)) continue;
      const double wb = k & (1 << b) ? c.f[b] : 1 - c.f[b];
      const double wd = k & (1 << d) ? c.f[d] : 1 - c.f[d];
      grad[a] += (c.corner[k | (1 << a)] - c.corner[k]) * wb * wd;
    }
  }
  return grad;
}

// Trilinear density at continuous grid coordinates g, clamped at the grid's edges.
DV_HD inline double density_at_grid(const SceneView& s, const VolumeView& v, const dvec3& g) {
  return trilinear(grid_cell(s, v, g));
}

struct TransferSample {
  dvec3 color;
  double sigma;
};

// The transfer function's segment [p[k], p[k + 1]] holding a density strictly inside its range
// (p[0].density < density < p[n - 1].density; the callers answer the constant ends themselves;
// evaluate_transfer here, the oracle's transfer_piece in engine/oracle/volume_chord.h).
DV_HD inline int transfer_segment(const TransferPoint* p, int n, double density) {
  int k = 0;
  while (k + 1 < n - 1 && p[k + 1].density <= density) ++k;
  return k;
}

// Piecewise-linear transfer function over n >= 1 points sorted by density; the end points'
// values hold outside their range.
DV_HD inline TransferSample evaluate_transfer(const TransferPoint* p, int n, double density) {
  if (density <= p[0].density) return {p[0].color, p[0].sigma};
  if (density >= p[n - 1].density) return {p[n - 1].color, p[n - 1].sigma};
  const int k = transfer_segment(p, n, density);
  const double span = p[k + 1].density - p[k].density;
  const double w = span > 0.0 ? (density - p[k].density) / span : 1.0;
  return {p[k].color * (1.0 - w) + p[k + 1].color * w, p[k].sigma * (1.0 - w) + p[k + 1].sigma * w};
}

// An antiderivative of the transfer function's extinction over density, exact for the
// piecewise-linear function and its constant ends: integral of sigma from p[0].density to x.
DV_HD inline double transfer_sigma_integral(const TransferPoint* p, int n, double x) {
  if (x <= p[0].density) return (x - p[0].density) * p[0].sigma;
  double total = 0.0;
  for (int k = 0; k + 1 < n; ++k) {
    const double lo = p[k].density, hi = p[k + 1].density;
    if (x <= hi) {
      const double w = hi > lo ? (x - lo) / (hi - lo) : 1.0;
      const double sigma_x = p[k].sigma * (1.0 - w) + p[k + 1].sigma * w;
      return total + 0.5 * (p[k].sigma + sigma_x) * (x - lo);
    }
    total += 0.5 * (p[k].sigma + p[k + 1].sigma) * (hi - lo);
  }
  return total + (x - p[n - 1].density) * p[n - 1].sigma;
}

// The mean extinction over the densities between x and y (pre-integration, Engel et al. 2001:
// a step whose density runs linearly from x to y absorbs its length times this mean).
DV_HD inline double transfer_sigma_mean(const TransferPoint* p, int n, double x, double y) {
  if (fabs(y - x) <= 1e-7 * (fabs(x) + fabs(y) + 1e-30))
    return evaluate_transfer(p, n, 0.5 * (x + y)).sigma;
  return (transfer_sigma_integral(p, n, y) - transfer_sigma_integral(p, n, x)) / (y - x);
}

// An object's transfer function at a density.
DV_HD inline TransferSample apply_transfer(const SceneView& s, const ObjectView& o,
                                           double density) {
  return evaluate_transfer(s.transfer.data + o.transfer_first, o.transfer_count, density);
}

// Extinction of a volume object at a world point.
DV_HD inline double volume_sigma(const SceneView& s, const ObjectView& o, const dvec3& world) {
  const VolumeView& v = s.volumes[o.volume];
  return apply_transfer(s, o, density_at_grid(s, v, world_to_grid(o, world))).sigma;
}

// World-space gradient from a gradient in grid units: d(density)/d(world) = J^T d/d(grid), J the
// linear part of world_to_grid.
DV_HD inline dvec3 world_gradient(const ObjectView& o, const dvec3& grid_gradient) {
  return glm::transpose(glm::dmat3(o.world_to_grid)) * grid_gradient;
}

// Where brick `brick` of object o is flagged in SceneView::brick_empty.
DV_HD inline int64_t brick_flag_index(const ObjectView& o, const ivec3& brick) {
  return o.brick_offset + (int64_t(brick.z) * o.bricks.y + brick.y) * o.bricks.x + brick.x;
}

// Empty-space skipping (Hadwiger et al. 2006, §3): bricks of kBrickCells^3 cells whose samples
// map to zero extinction under the object's transfer function are flagged when the scene is
// flattened. Coordinates outside the grid clamp, so the first and last bricks extend to
// infinity on their outer sides.
DV_HD inline ivec3 brick_of_grid_point(const SceneView& s, const ObjectView& o, const dvec3& g) {
  const VolumeView& v = s.volumes[o.volume];
  ivec3 brick;
  for (int a = 0; a < 3; ++a) {
    const double c = clamp_value(g[a], 0.0, double(v.dims[a] - 1));
    brick[a] = min_value(int(c) / kBrickCells, o.bricks[a] - 1);
  }
  return brick;
}

DV_HD inline bool in_empty_brick(const SceneView& s, const ObjectView& o, const dvec3& g,
                                 ivec3& brick) {
  brick = brick_of_grid_point(s, o, g);
  return s.brick_empty[brick_flag_index(o, brick)] != 0;
}

// How far along the ray (world units) from grid point g, moving gd grid units per world unit,
// until it leaves `brick`.
DV_HD inline double brick_exit_distance(const ObjectView& o, const ivec3& brick, const dvec3& g,
                                        const dvec3& gd) {
  double t = 1e300;
  for (int a = 0; a < 3; ++a) {
    if (gd[a] > 0.0 && brick[a] < o.bricks[a] - 1)
      t = min_value(t, (double((brick[a] + 1) * kBrickCells) - g[a]) / gd[a]);
    if (gd[a] < 0.0 && brick[a] > 0)
      t = min_value(t, (double(brick[a] * kBrickCells) - g[a]) / gd[a]);
  }
  return t > 0.0 ? t : 0.0;
}

// How much of the ray origin + t dir, t >= t_min, lies in bricks of volume object o's grid that
// are not empty (world units): the stretch a march samples rather than jumps, before the
// object's boundary, occluders or saturation cut it short. A cost estimate for ordering work
// (render/frame/fragment_lanes.h), so it walks brick by brick with additions only (Amanatides and
// Woo's grid traversal) and one flag load per brick.
DV_HD inline double occupied_brick_length(const SceneView& s, const ObjectView& o,
                                          const dvec3& origin, const dvec3& dir, double t_min) {
  const dvec3 g0 = dvec3(o.world_to_grid * dvec4(origin, 1.0));
  const dvec3 gd = dvec3(o.world_to_grid * dvec4(dir, 0.0));
  const Aabb grid{dvec3(0.0), dvec3(s.volumes[o.volume].dims - 1)};
  double t0 = t_min, t1 = 1e300;
  if (!clip_ray_to_box(g0, gd, 1.0 / gd, grid, t0, t1) || !(t0 < t1)) return 0.0;
  // The first brick is the one just past the entry, found as the sampling finds bricks; from
  // there each step crosses the nearest brick face.
  ivec3 step;
  dvec3 next, delta;
  const double t_start = t0 + 0.5 * min_value(t1 - t0, 1e-6);
  ivec3 brick = brick_of_grid_point(s, o, g0 + gd * t_start);
  for (int a = 0; a < 3; ++a) {
    step[a] = gd[a] > 0.0 ? 1 : gd[a] < 0.0 ? -1 : 0;
    delta[a] = step[a] != 0 ? double(kBrickCells) / fabs(gd[a]) : 1e300;
    const int face = (brick[a] + (step[a] > 0 ? 1 : 0)) * kBrickCells;
    next[a] = step[a] != 0 ? (double(face) - g0[a]) / gd[a] : 1e300;
  }
  double length = 0.0, t = t0;
  while (t < t1) {
    const int a = next.x <= next.y && next.x <= next.z ? 0 : next.y <= next.z ? 1 : 2;
    const double exit = min_value(next[a], t1);
    if (!s.brick_empty[brick_flag_index(o, brick)]) length += exit - t;
    t = exit;
    brick[a] += step[a];
    next[a] += delta[a];
    if (brick[a] < 0 || brick[a] >= o.bricks[a]) break;
  }
  return length;
}

}  // namespace dv
