// The `sat` conservative surface voxelizer (Schwarz & Seidel 2010; Buchacher 2014 §3.3) on the
// CPU or CUDA backend: every voxel whose closed box meets a triangle, by the plane test plus
// three 2D edge-function projections (sat_kernels.h), with large triangles split into one work
// item per voxel column so they do not serialise on one thread. CPU and CUDA grids are
// identical.
#pragma once

#include "strategies/voxelizer/voxelizer.h"

namespace dv {

// Passes: clear, upload, setup, scan, voxelize. Counters: triangles, work_items,
// degenerate_triangles (those voxelized as segments or points).
VoxelizeResult voxelize_sat(Backend backend, const TriangleSoup& soup, const GridSpec& spec);

}  // namespace dv
