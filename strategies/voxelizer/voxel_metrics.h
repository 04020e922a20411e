// How a voxelizer's grid compares with the exact reference: filled voxels, missing ones
// (reference minus output: a conservativeness violation), extra ones (output minus reference),
// and both again outside the borderline band (exact_voxelizer.h), where membership does not
// depend on rounding. Outside the band: missing = shrunk minus output, extra = output minus
// grown.
#pragma once

#include <cstdint>

#include <nlohmann/json.hpp>

#include "strategies/voxelizer/exact_voxelizer.h"

namespace dv {

struct VoxelMetrics {
  int64_t filled = 0;            // voxels the method set
  int64_t reference_filled = 0;  // voxels of the exact set
  int64_t missing = 0;
  int64_t extra = 0;
  int64_t borderline = 0;  // grown but not shrunk
  int64_t missing_outside_band = 0;
  int64_t extra_outside_band = 0;

  nlohmann::json to_json() const;
};

// `reference` must carry the band (voxelize_exact with_band = true) and share `method`'s grid
// size; `method` may live in either memory. Throws Error otherwise.
VoxelMetrics compare_with_exact(const VoxelGrid& method, const ExactVoxelization& reference);

}  // namespace dv
