// The `atlas` voxelizer in OpenGL (Thiedemann et al. 2011; Buchacher 2014 §3.2), run headless
// through EGL over the same atlas as the CPU/CUDA version (strategies/voxelizer/atlas_packing.h,
// atlas_voxelizer.h), in two passes:
//   atlas_update: the triangles drawn at their atlas positions into an RGBA32F position texture
//     (side x side, a framebuffer attachment cleared to zero). The interpolated attribute is the
//     corner's homogeneous grid position (X, Y, Z, W), affine in the world point, so that linear
//     interpolation gives exactly the texel's surface point: box grids (grid x, y, z, 1);
//     frustum grids X, Y the grid x, y times the clip w, Z the grid depth, W the clip w
//     (GridTransform in voxel_grid.h); it travels as the triangle's first corner (flat) plus
//     the interpolated offset from it, which rounds less than the position itself. Alpha > 0 marks
//     a texel whose point lies in front of the grid's eye (every covered texel of a box grid);
//     uncovered texels stay zero.
//   points: GL_POINTS, one per atlas texel, whose vertex shader reads its texel, divides X, Y by
//     W and ORs the bit of the half-open voxel holding the point into the r32ui array image of
//     gl_grid_image.h (rasterizer discard: no fragments).
// The packing keeps every texel centre off the cell's edges, so the driver covers the same
// texels as the tile rasterizer; grids differ only where float interpolation rounds a point
// across a voxel face (the CPU computes the points in double).
#pragma once

#include "strategies/voxelizer/voxelizer.h"

namespace dv::gl {

// Needs a current OpenGL 4.5 context (EglContext) with image stores in vertex shaders. Passes:
// clear, pack (host), upload, program, atlas_update, points, readback (glFinish between them,
// host clock). Counters: triangles, skipped_triangles (corners not finite in float grid
// coordinates: their cells stay empty), atlas_side, texel_size, valid_texels, renderer. The grid
// comes back in host memory. Throws InputError for an atlas side outside [1, kMaxAtlasSide] or
// beyond the driver's texture or framebuffer size, and for grids beyond its limits.
VoxelizeResult voxelize_atlas_gl(const TriangleSoup& soup, const GridSpec& spec, int atlas_side);

}  // namespace dv::gl
