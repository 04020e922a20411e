// Shared CPU/CUDA arithmetic of the atlas voxelizers (layout in atlas_packing.h): a cell's
// texels in diagonal order, the atlas position of a triangle's corners, the surface point of a
// texel, and writing a point into the grid. `atlas` (rasterized) and `atlas-compute` call the
// same functions, so their grids are identical.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/hd.h"
#include "core/math.h"
#include "strategies/voxelizer/atlas_packing.h"
#include "strategies/voxelizer/voxel_geometry.h"
#include "strategies/voxelizer/voxel_grid.h"

namespace dv {

DV_HD inline int64_t atlas_cell_texels(int32_t size) {
  return int64_t(size) * (size + 1) / 2;
}

// Texel (i, j) of a cell's `local`-th valid texel, counted along the diagonals d = i + j
// (d (d + 1) / 2 texels come before diagonal d).
DV_HD inline void atlas_texel_of(int64_t local, int& i, int& j) {
  int64_t d = int64_t((::sqrt(8.0 * double(local) + 1.0) - 1.0) * 0.5);
  while (d * (d + 1) / 2 > local) --d;
  while ((d + 1) * (d + 2) / 2 <= local) ++d;
  i = int(local - d * (d + 1) / 2);
  j = int(d) - i;
}

// Atlas position (texel units, x right, y down) of corner m of the cell's triangle.
DV_HD inline dvec3 atlas_corner_position(const AtlasCell& cell, int m) {
  const int role = (m - cell.corner + 3) % 3;  // 0: right angle, 1: along x, 2: along y
  const double leg = double(cell.size) + 0.5;
  return dvec3(double(cell.x) + (role == 1 ? leg : 0.0), double(cell.y) + (role == 2 ? leg : 0.0),
               0.0);
}

// World-space surface point of texel (i, j) of the cell of triangle `corners` (3 world points).
DV_HD inline dvec3 atlas_point(const dvec3* corners, const AtlasCell& cell, int i, int j) {
  const dvec3& a = corners[cell.corner];
  const dvec3& b = corners[(cell.corner + 1) % 3];
  const dvec3& c = corners[(cell.corner + 2) % 3];
  const double leg = double(cell.size) + 0.5;
  const double u = (double(i) + 0.5) / leg, v = (double(j) + 0.5) / leg;
  return a + u * (b - a) + v * (c - a);
}

// Sets the voxel holding world point p (none outside the grid's closed box).
DV_HD inline void atlas_write_point(const VoxelGridView& grid, const GridTransform& to_grid,
                                    const dvec3& p) {
  ivec3 v;
  if (point_voxel_index(to_grid.apply(p), ivec3(grid.width, grid.height, grid.depth), v))
    grid.set(v.x, v.y, v.z);
}

}  // namespace dv
