// binvox files (Min's format, readable by viewvox, binvox-rw and other voxel tools) for the
// voxel grids: an ASCII header
//     #binvox 1
//     dim X Z Y
//     translate tx ty tz
//     scale s
//     data
// then run-length pairs of bytes (value 0 or 1, count 1..255) over the voxels with x outermost,
// then z, then y innermost (index x * Z*Y + z * Y + y). The format names its dims "depth,
// height, width" and indexes x * (width*height) + z * width + y, so depth is our W (x count),
// height our D (z count) and width our H (y count); tools that assume cubic grids read any
// order. Voxel (i, j, k) has its centre at translate + scale * ((i, j, k) + 0.5) / max(W, H, D):
// binvox holds one scale, exact only for cubic voxels, so callers keep the exact bounds
// elsewhere (the voxelize stats do).
#pragma once

#include <string>

#include "strategies/voxelizer/voxel_grid.h"

namespace dv {

// Writes `grid` (host or device memory) with translate = bounds.lo and
// scale = voxel width in x * max(W, H, D). Throws InputError naming the path on failure.
void write_binvox(const std::string& path, const VoxelGrid& grid);

struct BinvoxFile {
  VoxelGrid grid;  // host memory; bounds rebuilt from translate and scale
  dvec3 translate{0.0};
  double scale = 1.0;
};

// Reads a version-1 binvox file whose z count is a multiple of 32 (what the grid can hold);
// missing translate/scale lines mean 0 and 1. Throws InputError naming the path for anything
// malformed: bad header, sizes, values other than 0/1, zero counts, too few or too many voxels.
BinvoxFile read_binvox(const std::string& path);

}  // namespace dv
