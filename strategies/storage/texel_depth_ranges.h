// The `range` pass of the storages that fold a texel into a fixed record (moments, fourier,
// occupancy; optical_depth_basis.h):
// one generation walk per texel that writes the depths of its first and last node into the
// first two floats of its record (texel t's record at t * stride), and keeps the nodes for the
// write pass in `replay` (engine/dsm/node_replay.h). Compiled by nvcc when CUDA is on
// (texel_depth_ranges.cpp).
#pragma once

#include "engine/dsm/node_replay.h"
#include "strategies/storage/dsm_storage.h"

namespace dv {

void write_texel_depth_ranges(const DsmGenerationContext& c, NodeReplay replay, View<float> data,
                              int stride);

}  // namespace dv
