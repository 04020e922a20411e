// Host-side helpers of the tile lists (views, host copies, the split into sets of
// tile_list_sets.h) and the stats as JSON for the render stats file. Kept out of tile_raster.cpp
// so nvcc compiles only the kernels.
#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/raster/tile_list_sets.h"
#include "engine/raster/tile_raster.h"

namespace dv {

TileListsView TileListBuffers::view(int projection) const {
  const int64_t tiles = tile_count();
  const View<const uint32_t> all = offsets.const_view();
  return {width,
          height,
          tiles_x,
          tiles_y,
          {all.data + projection * tiles, tiles + 1},
          entries.const_view()};
}

std::vector<TileListSet> rasterize_tile_sets(Backend backend, View<const dvec3> vertices,
                                             View<const u32vec3> triangles,
                                             const std::vector<RasterProjection>& projections,
                                             const RasterOptions& options) {
  const size_t most = size_t(tile_set_projections(triangles.size));
  std::vector<TileListSet> sets;
  for (size_t first = 0; first < projections.size();) {
    const RasterProjection& lead = projections[first];
    size_t end = first + 1;
    while (end < projections.size() && end - first < most && projections[end].width == lead.width &&
           projections[end].height == lead.height)
      ++end;
    const std::vector<RasterProjection> set(projections.begin() + std::ptrdiff_t(first),
                                            projections.begin() + std::ptrdiff_t(end));
    sets.push_back(rasterize_tile_set(backend, vertices, triangles, set, options));
    first = end;
  }
  return sets;
}

TileListBuffers TileListBuffers::to_host() const {
  const std::vector<uint32_t> host_offsets = offsets.to_vector();
  const std::vector<TileEntry> host_entries = entries.to_vector();
  return {
      width,
      height,
      tiles_x,
      tiles_y,
      Buffer<uint32_t>(Memory::host, std::span<const uint32_t>(host_offsets), "tile offsets"),
      Buffer<TileEntry>(Memory::host, std::span<const TileEntry>(host_entries), "tile entries")};
}

TileLists TileLists::to_host() const {
  return {TileListBuffers::to_host(), stats};
}

void to_json(nlohmann::json& out, const RasterStats& s) {
  out = {{"triangles_in", s.triangles_in},
         {"triangles_rasterized", s.triangles_rasterized},
         {"triangles_clipped", s.triangles_clipped},
         {"clipped_near", s.clipped_near},
         {"clipped_guard", s.clipped_guard},
         {"triangles_culled", s.triangles_culled},
         {"culled_behind", s.culled_behind},
         {"culled_offscreen", s.culled_offscreen},
         {"culled_degenerate", s.culled_degenerate},
         {"culled_invalid", s.culled_invalid},
         {"pieces", s.pieces},
         {"entries", s.entries},
         {"entries_needed", s.entries_needed},
         {"max_entries_per_tile", s.max_entries_per_tile},
         {"overflow", s.overflow},
         {"first_incomplete_tile", s.first_incomplete_tile},
         {"dropped_tiles", s.dropped_tiles}};
}

}  // namespace dv
