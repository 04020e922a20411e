// Voxel grids over a light's frustum: one grid per light-map face of
// engine/raster/light_faces.h, orthographic for directional lights and perspective for spot
// lights and omni faces, columns = the face's texels, slices = planes at equal distances along
// the face's axis between the casters' nearest and farthest depth (voxel_grid.h, kinds
// orthographic and perspective). Reuses the faces rather than building frusta of its own.
#pragma once

#include <string>

#include "core/math.h"
#include "engine/raster/light_faces.h"
#include "strategies/voxelizer/voxel_grid.h"

namespace dv {

// A validated grid of res x res columns and `depth` slices over `face`, its depth range fitted
// to `casters` along the face's axis (padded so that flat or empty caster sets still give a
// range; perspective grids start in front of the light). Throws InputError(where) for bad sizes.
GridSpec make_light_grid(const ShadowFace& face, int res, int depth, const Aabb& casters,
                         const std::string& where = "light grid");

}  // namespace dv
