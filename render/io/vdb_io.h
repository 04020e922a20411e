// OpenVDB volumes (.vdb files from Houdini, Blender, EmberGen...) as scene volumes, and the
// voxelizer's occupancy written as a .vdb. OpenVDB stores a sparse tree over an integer index
// space; a linear transform places index (i, j, k) in the world. Its value at index (i, j, k)
// is a point sample there (OpenVDB's samplers interpolate between those points), so it maps
// one to one onto deepvox's vertex-centred VolumeGrid (engine/scene/scene.h) without any
// resampling:
//   - the grid read is the float grid named `grid_name` ("density" unless the scene names
//     another); a missing name lists the grids present with their value types, a grid of
//     another value type is an error naming that type;
//   - the dense box is the grid's active voxel bounding box grown by one voxel on every side, so
//     the edge samples hold what lies just outside the active voxels (normally the background)
//     and deepvox's clamp-to-edge lookups outside the box read that, as OpenVDB would: inside the
//     box, trilinear lookups equal openvdb::tools::BoxSampler's;
//   - every value in the box is read as the tree stores it, active or not: tiles are expanded
//     to their voxels, inactive voxels give their stored value (the background in fog volumes);
//   - the transform must be linear and axis aligned with positive voxel sizes (any translation,
//     a different voxel size per axis allowed): origin = the world position of the box's
//     minimum index, spacing = the voxel size. Rotated, sheared, mirrored and frustum
//     (non-linear) transforms are rejected with an error saying so: rotate the object instead
//     (its "transform" in the scene) or resample the grid to an axis-aligned transform first;
//   - at most kMaxVolumeVoxels samples (render/io/volume_io.h) after the one-voxel border; a
//     larger box is an error naming the file, the box and the bytes the dense grid would need;
//   - every value must be finite.
// Every error is an InputError naming the file; OpenVDB's own errors (bad magic, a truncated
// file, an unknown compression) are passed on in its words. The lean build has no OpenVDB
// (vdb_unavailable.cpp): there every function but vdb_supported throws an InputError naming the
// file and saying "built without OpenVDB".
#pragma once

#include <string>

#include "engine/scene/scene.h"
#include "strategies/voxelizer/voxel_grid.h"

namespace dv {

// The grid a scene volume reads when it names none.
inline constexpr const char* kDefaultVdbGrid = "density";

// Whether this program was linked with OpenVDB (render/io/CMakeLists.txt).
bool vdb_supported();
// Nothing where vdb_supported(); else the InputError naming `path` that every VDB function
// throws, for commands that check their outputs before any work.
void require_vdb_support(const std::string& path);

// Reads grid `grid_name` of the .vdb file at `path` as described above; the result's name is
// the path.
VolumeGrid load_vdb_volume(const std::string& path, const std::string& grid_name = kDefaultVdbGrid);

// Writes a box-kind voxel grid (host or device memory) as a fog volume: a float grid named
// "density", 1 in every set voxel, background 0 (unset voxels inactive), with the transform
// that puts index (i, j, k) at the centre of voxel (i, j, k): translation bounds.lo + half a
// voxel, voxel size bounds.extent() / res per axis. Light-frustum grids have no linear
// placement and are rejected.
void write_vdb_occupancy(const std::string& path, const VoxelGrid& grid);

}  // namespace dv
