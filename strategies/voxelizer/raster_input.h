// The triangle soup as the shared tile rasterizer takes it (engine/raster/tile_raster.h):
// three vertices per triangle and the trivial index list (3i, 3i+1, 3i+2), filled by the
// rasterizing voxelizers' setup kernels (slicemap: corners in grid coordinates; atlas: corners
// at their atlas texel positions), plus the checks both need.
#pragma once

#include <cstdint>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/math.h"
#include "cuda/buffer.h"
#include "cuda/execute.h"
#include "engine/raster/tile_raster.h"

namespace dv {

struct RasterInput {
  Buffer<dvec3> vertices;     // 3 per triangle
  Buffer<u32vec3> triangles;  // triangle i: (3i, 3i+1, 3i+2)

  RasterInput(Memory memory, int64_t count)
      : vertices(memory, 3 * count, "raster vertices"),
        triangles(memory, count, "raster triangles") {}

  RasterView view(const RasterProjection& projection) const {
    return {projection, vertices.const_view(), triangles.const_view()};
  }
};

// Throws InputError(where) when `triangles` triangles do not fit 32-bit vertex indices.
inline void check_raster_triangle_count(int64_t triangles, const std::string& where) {
  if (triangles > int64_t(std::numeric_limits<uint32_t>::max() / 3))
    throw InputError(where, std::to_string(triangles) +
                                " triangles exceed the rasterizer's 32-bit vertex indices");
}

// Throws Error(where) when the rasterizer's tile lists overflowed (fragments would be lost).
inline void check_tile_lists(const TileLists& lists, const std::string& where) {
  if (lists.stats.overflow)
    throw Error(where + ": tile lists overflowed (" + std::to_string(lists.stats.entries_needed) +
                " entries needed)");
}

}  // namespace dv
