// Binning the faces of many lights: the projections split into tile-list sets (runs of one
// image size, at most tile_set_projections(triangles) projections a set, so that a set's records
// stay within about 340 MB), each binned by rasterize_tile_set in one run of the rasterizer's
// passes. Shared by deep shadow map generation and the depth shadow maps.
#pragma once

#include <vector>

#include "engine/raster/tile_raster.h"

namespace dv {

// The sets over `projections`, in order: projection k is the k-th over the sets' projections.
std::vector<TileListSet> rasterize_tile_sets(Backend backend, View<const dvec3> vertices,
                                             View<const u32vec3> triangles,
                                             const std::vector<RasterProjection>& projections,
                                             const RasterOptions& options = {});

}  // namespace dv
