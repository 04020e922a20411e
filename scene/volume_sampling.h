// Sampling of density volumes for host and device: trilinear interpolation of vertex-centred
// samples (clamped at the edges), the piecewise-linear transfer function, and the density
// gradient used as the shading normal. Shared by the oracle and every renderer.
#pragma once

#include "core/hd.h"
#include "core/math.h"
#include "scene/scene_view.h"

namespace dv {

DV_HD inline dvec3 world_to_grid(const ObjectView& o, const dvec3& world) {
  return dvec3(o.world_to_grid * dvec4(world, 1.0));
}

DV_HD inline double sample_at(const SceneView& s, const VolumeView& v, int x, int y, int z) {
  return double(s.densities[v.offset + (int64_t(z) * v.dims.y + y) * v.dims.x + x]);
}

// Trilinear density at continuous grid coordinates g (sample i sits at g = i).
DV_HD inline double density_at_grid(const SceneView& s, const VolumeView& v, const dvec3& g) {
  int i0[3];
  double f[3];
  for (int a = 0; a < 3; ++a) {
    const double hi = double(v.dims[a] - 1);
    const double c = clamp_value(g[a], 0.0, hi);
    int i = int(c);  // c >= 0, so truncation is floor
    if (i > v.dims[a] - 2) i = v.dims[a] - 2 < 0 ? 0 : v.dims[a] - 2;
    i0[a] = i;
    f[a] = v.dims[a] > 1 ? c - double(i) : 0.0;
  }
  const int x1 = v.dims.x > 1 ? i0[0] + 1 : i0[0];
  const int y1 = v.dims.y > 1 ? i0[1] + 1 : i0[1];
  const int z1 = v.dims.z > 1 ? i0[2] + 1 : i0[2];
  const double c00 =
      sample_at(s, v, i0[0], i0[1], i0[2]) * (1 - f[0]) + sample_at(s, v, x1, i0[1], i0[2]) * f[0];
  const double c10 =
      sample_at(s, v, i0[0], y1, i0[2]) * (1 - f[0]) + sample_at(s, v, x1, y1, i0[2]) * f[0];
  const double c01 =
      sample_at(s, v, i0[0], i0[1], z1) * (1 - f[0]) + sample_at(s, v, x1, i0[1], z1) * f[0];
  const double c11 =
      sample_at(s, v, i0[0], y1, z1) * (1 - f[0]) + sample_at(s, v, x1, y1, z1) * f[0];
  const double c0 = c00 * (1 - f[1]) + c10 * f[1];
  const double c1 = c01 * (1 - f[1]) + c11 * f[1];
  return c0 * (1 - f[2]) + c1 * f[2];
}

struct TransferSample {
  dvec3 color;
  double sigma;
};

// Piecewise-linear transfer function; the end points' values hold outside their range.
DV_HD inline TransferSample apply_transfer(const SceneView& s, const ObjectView& o,
                                           double density) {
  const TransferPoint* p = s.transfer.data + o.transfer_first;
  const int n = o.transfer_count;
  if (density <= p[0].density) return {p[0].color, p[0].sigma};
  if (density >= p[n - 1].density) return {p[n - 1].color, p[n - 1].sigma};
  int k = 0;
  while (k + 1 < n - 1 && p[k + 1].density <= density) ++k;
  const double span = p[k + 1].density - p[k].density;
  const double w = span > 0.0 ? (density - p[k].density) / span : 1.0;
  return {p[k].color * (1.0 - w) + p[k + 1].color * w, p[k].sigma * (1.0 - w) + p[k + 1].sigma * w};
}

// Extinction of a volume object at a world point.
DV_HD inline double volume_sigma(const SceneView& s, const ObjectView& o, const dvec3& world) {
  const VolumeView& v = s.volumes[o.volume];
  return apply_transfer(s, o, density_at_grid(s, v, world_to_grid(o, world))).sigma;
}

// World-space density gradient by central differences of one grid cell.
DV_HD inline dvec3 density_gradient(const SceneView& s, const ObjectView& o, const dvec3& world) {
  const VolumeView& v = s.volumes[o.volume];
  const dvec3 g = world_to_grid(o, world);
  dvec3 grad_grid;
  for (int a = 0; a < 3; ++a) {
    dvec3 d(0.0);
    d[a] = 0.5;
    grad_grid[a] = density_at_grid(s, v, g + d) - density_at_grid(s, v, g - d);
  }
  // d(density)/d(world) = J^T d(density)/d(grid), J the linear part of world_to_grid.
  return glm::transpose(glm::dmat3(o.world_to_grid)) * grad_grid;
}

// Empty-space skipping (Hadwiger et al. 2006, §3): bricks of kBrickCells^3 cells whose samples
// map to zero extinction under the object's transfer function are flagged when the scene is
// flattened. Coordinates outside the grid clamp, so the first and last bricks extend to
// infinity on their outer sides.
DV_HD inline bool in_empty_brick(const SceneView& s, const ObjectView& o, const dvec3& g,
                                 ivec3& brick) {
  const VolumeView& v = s.volumes[o.volume];
  for (int a = 0; a < 3; ++a) {
    const double c = clamp_value(g[a], 0.0, double(v.dims[a] - 1));
    brick[a] = min_value(int(c) / kBrickCells, o.bricks[a] - 1);
  }
  return s.brick_empty[o.brick_offset + (int64_t(brick.z) * o.bricks.y + brick.y) * o.bricks.x +
                       brick.x] != 0;
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

}  // namespace dv
