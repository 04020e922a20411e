// The `slicemap` voxelizer in OpenGL (Eisemann & Decoret 2006; Buchacher 2014 §3.1), run
// headless through EGL: the same camera and rules as the CPU/CUDA version
// (strategies/voxelizer/slicemap_voxelizer.h). Vertices go to the GPU in grid coordinates
// (float), window x, y = grid x, y, and each fragment ORs the bit of the slice holding its
// interpolated grid depth into an r32ui 2D array image with imageAtomicOr: layer k holds slices
// 32k..32k+31, exactly VoxelGrid's word layout, so any depth that is a multiple of 32 works (up
// to the driver's array-layer limit; 1024 needs 32 layers). No render target (a framebuffer
// without attachments), no depth test, no culling.
//
// Agreement with the shared rasterizer: where the driver samples coverage at pixel centres with
// the same top-left tie rule and 1/256-pixel snapping, only fragments whose float depth rounds
// across a slice plane, or whose float vertices snap differently, can differ.
#pragma once

#include "strategies/voxelizer/voxelizer.h"

namespace dv::gl {

// Needs a current OpenGL 4.5 context (EglContext). Passes: clear, upload, program (shader
// compilation), voxelize, readback (glFinish between them, host clock). Counters: triangles,
// skipped_triangles (corners not finite in grid coordinates), renderer (GL_RENDERER). The grid
// comes back in host memory. Throws InputError when the grid exceeds the driver's limits.
VoxelizeResult voxelize_slicemap_gl(const TriangleSoup& soup, const GridSpec& spec);

}  // namespace dv::gl
