// The `sat` conservative surface voxelizer (Schwarz & Seidel 2010; Buchacher 2014 §3.3) on the
// CPU or CUDA backend: every voxel whose closed box meets a triangle, by the plane test plus
// three 2D edge-function projections (sat_device.h). Triangles are classified by the size of
// their voxel footprint: small ones (at most `small_items` work items: voxel columns, or slices
// of a degenerate one) are voxelized whole by one thread, large ones split into one work item
// per column so they do not serialise on one thread. CPU and CUDA grids are identical, and do
// not depend on `small_items`.
#pragma once

#include <cstdint>

#include "strategies/voxelizer/voxelizer.h"

namespace dv {

// Default footprint limit of a triangle voxelized by one thread (the `small` parameter): the
// fastest of 32, 64, 128 and 256 for the bunny x2 at 1024^3 in bench_voxelizer's sweep
// (results/perf), where most triangles have 64-256 columns; at 512^3 nearly all are small anyway.
inline constexpr int64_t kSatSmallItems = 256;
// Its upper limit (a million columns on one thread: far past any sensible split).
inline constexpr int64_t kSatMaxSmallItems = int64_t(1) << 20;

// Throws InputError unless small_items is in [0, kSatMaxSmallItems].
void validate_sat_small_items(int64_t small_items);

// Passes: upload, clear, small (classification, and the small triangles voxelized), large.
// Counters: triangles, work_items, large_triangles, degenerate_triangles (those voxelized as
// segments or points).
// `max_batch` > 0 caps the triangles per large list below what packed_work_list_batch allows
// (work_items.h; tests of the batched route, which otherwise needs enormous grids).
VoxelizeResult voxelize_sat(Backend backend, const TriangleSoup& soup, const GridSpec& spec,
                            int64_t small_items = kSatSmallItems, int64_t max_batch = 0);

}  // namespace dv
