// The texture-atlas voxelizers on the CPU or CUDA backend, both point methods over the atlas of
// atlas_packing.h (one surface point per valid texel, written into the half-open voxel holding
// it):
//   `atlas` (Thiedemann et al. 2011; Buchacher 2014 §3.2): the atlas update rasterizes the
//     triangles at their atlas positions with the shared tile rasterizer and stores each covered
//     texel's world position in a position texture; a second pass writes one point per valid
//     texel into the grid.
//   `atlas-compute` (Buchacher §3.4): no rasterization; one compute thread per valid texel
//     computes its point and writes it.
// Both use the same texel points (atlas_device.h), so their grids are identical.
#pragma once

#include "strategies/voxelizer/voxelizer.h"

namespace dv {

inline constexpr int kDefaultAtlasSide = 1024;
// The `atlas` parameter of the atlas voxelizers (CPU, CUDA and OpenGL): texels per side.
ParamSpec atlas_side_param();

// Passes: clear, pack (the atlas layout, host), upload, atlas_update (rasterization into the
// position texture), points. Counters: triangles, atlas_side, texel_size, valid_texels, raster.
VoxelizeResult voxelize_atlas(Backend backend, const TriangleSoup& soup, const GridSpec& spec,
                              int atlas_side);
// Passes: clear, pack, upload, points. Counters as above without raster.
VoxelizeResult voxelize_atlas_compute(Backend backend, const TriangleSoup& soup,
                                      const GridSpec& spec, int atlas_side);

}  // namespace dv
