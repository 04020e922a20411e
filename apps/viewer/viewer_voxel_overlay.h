// The viewer's voxel grid overlay: the set voxels of a shadow method's light grids (the
// transmittance slicemap's, ShadowMethod::voxel_grids) as world-space points at the voxel
// centres, which the window projects with the current camera (GL points). A frustum grid's
// voxel (x, y, z) is centred on the ray through image point (x + 0.5, y + 0.5) of its face, at
// axial depth near + (z + 0.5) * (far - near) / D (voxel_grid.h conventions).
#pragma once

#include <cstdint>
#include <vector>

#include "core/math.h"
#include "strategies/voxelizer/voxel_grid.h"

namespace dv::viewer {

struct VoxelPoints {
  std::vector<float> positions;  // x, y, z per set voxel, world space
  std::vector<float> depths;     // per set voxel: (z + 0.5) / D, 0 nearest the light
  int grids = 0;
  int64_t count() const { return int64_t(depths.size()); }
};

// The world-space centre of voxel (x, y, z) of `spec`.
dvec3 voxel_centre(const GridSpec& spec, int x, int y, int z);

// Appends the centres of the set voxels of `grid` (device grids are copied to the host).
void add_set_voxels(const VoxelGrid& grid, VoxelPoints& out);

}  // namespace dv::viewer
