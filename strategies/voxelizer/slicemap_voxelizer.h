// The `slicemap` voxelizer (Eisemann & Decoret 2006; Buchacher 2014 §3.1) on the CPU or CUDA
// backend: the grid's camera looks along +z of the grid (orthographic over the grid box, pixel
// (x, y) = voxel column (x, y), depth = grid z); the shared tile rasterizer
// (engine/raster/tile_raster.h) finds the triangles covering each pixel centre with its
// top-left rule, and each such fragment sets the voxel of its slice: the half-open cell holding
// the triangle's depth at the pixel centre (voxel_geometry.h point_voxel). A binary surface
// voxelization, not a conservative one: faces parallel to the view direction are culled as
// zero-area triangles and set nothing (counter zero_area_triangles), steep faces leave gaps
// along z, and triangles covering no pixel centre set nothing. The OpenGL version
// (gl/gl_slicemap.h) follows the same rules.
#pragma once

#include "strategies/voxelizer/voxelizer.h"

namespace dv {

// Passes: clear, upload, setup, raster, slices. Counters: triangles, zero_area_triangles (culled
// by the rasterizer: seen edge-on, or thinner than 1/256 pixel after snapping), raster (the
// rasterizer's RasterStats).
// Throws Error when the tile lists overflow.
VoxelizeResult voxelize_slicemap(Backend backend, const TriangleSoup& soup, const GridSpec& spec);

}  // namespace dv
