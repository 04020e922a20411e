// The grid a voxelization runs on, from text and from a mesh: "WxHxD" resolutions, explicit
// bounds, and the default bounds (the mesh box made cubic). Shared by `deepvox voxelize`, the
// experiment drivers and the benchmarks.
#pragma once

#include <string>

#include "core/math.h"

namespace dv {

// "WxHxD" (or "N" for N x N x N); every size is checked against the grid limits. Throws
// InputError(where, ...) with the reason.
ivec3 parse_voxel_resolution(const std::string& text, const std::string& where = "--res");
// "x0,y0,z0,x1,y1,z1" with x1 > x0, y1 > y0, z1 > z0, all finite.
Aabb parse_voxel_bounds(const std::string& text, const std::string& where = "--bounds");
// The cube with the same centre whose side is the box's largest extent; InputError(where)
// when the box is empty or has no extent at all.
Aabb cubic_bounds(const Aabb& box, const std::string& where);

}  // namespace dv
