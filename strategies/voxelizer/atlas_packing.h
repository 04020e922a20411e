// The texture atlas of the atlas voxelizers (Thiedemann et al. 2011; Buchacher 2014 §3.2, §3.4):
// a documented packing of the triangles into one square texture instead of a UV
// parameterization. Each triangle gets its own square cell of s x s texels and is mapped onto the
// right triangle in the cell's lower-left half: the corner opposite its longest edge at the
// cell's origin (texel corner (x, y)), the next corner at (x + s + 1/2, y), the last at
// (x, y + s + 1/2). The texel centres inside are exactly those (i, j) of the cell with
// i + j <= s - 1 (none lies on an edge, so every fill rule agrees): s (s + 1) / 2 texels, each a
// surface point at barycentric ((i + 1/2) / (s + 1/2), (j + 1/2) / (s + 1/2)) from the
// right-angle corner (atlas_device.h).
//
// Cell sizes follow triangle area, as a real atlas has one texel density: s = max(1,
// ceil(sqrt(2 * area) / texel_size)) with the area in grid units (voxels), so a texel_size of 1
// samples a right isosceles triangle about once per voxel along its legs. texel_size is the
// first value (starting from the density whose cells would just fill the atlas, growing by 5 %)
// for which shelf packing fits: cells by decreasing triangle area (then triangle index), placed
// left to right in rows as tall as their first cell, rows from y = 0 on. Long thin triangles get
// small cells and are undersampled, and a coarse atlas leaves holes (Buchacher §3.2.3): both show
// in the metrics against `exact`.
#pragma once

#include <cstdint>
#include <vector>

#include "strategies/voxelizer/triangle_soup.h"
#include "strategies/voxelizer/voxel_grid.h"

namespace dv {

// Largest atlas side accepted (the position texture holds 32 bytes per texel).
inline constexpr int kMaxAtlasSide = 4096;

struct AtlasCell {
  int32_t x = 0, y = 0;  // texel origin of the cell
  int32_t size = 0;      // s: the cell is s x s texels
  int32_t corner = 0;    // the triangle corner at the right angle (opposite its longest edge)
};

struct AtlasLayout {
  int side = 0;                      // texels per atlas side
  double texel_size = 0.0;           // grid units per texel along the legs, as used for the sizes
  std::vector<AtlasCell> cells;      // one per triangle
  std::vector<int64_t> texel_first;  // work_item_offsets of the cells' texel counts
  int64_t valid_texels() const { return texel_first.empty() ? 0 : texel_first.back(); }
};

// Packs every triangle of `soup` (sizes measured in the grid coordinates of `spec`) into a
// side x side atlas. Throws InputError when side is outside [1, kMaxAtlasSide] or the atlas
// cannot give every triangle its own texel.
AtlasLayout pack_atlas(const TriangleSoup& soup, const GridSpec& spec, int side);

}  // namespace dv
