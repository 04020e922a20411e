// Tile rasterizer of the shared renderer (Knecht 2011 §4.1): bins every
// triangle of a scene into per-8x8-tile lists of (64-bit coverage mask, triangle id), on CPU
// threads or CUDA from the same code, with identical results on both.
//
// Fixed point. After projection, pixel coordinates (x right, y down, pixel (i, j) spanning
// [i, i+1] x [j, j+1], its centre at (i + 0.5, j + 0.5)) are snapped to 1/256 pixel: int64
// values X = round(256 x), ties rounded up. Pixel centres are 256 i + 128. Everything after the
// snap is integer arithmetic, so coverage is exact and equal on every backend; the floating-
// point part before it (transform, clipping, division by w) uses IEEE operations without FMA
// contraction (the build forbids it), which round alike on CPU and GPU.
//
// Edge functions and fill rule. Both windings are rasterized: setup orders each triangle's
// corners so that E_e(p) = cross(v_{e+1} - v_e, p - v_e) is positive inside. A pixel centre is
// covered when all three E_e >= 0 and, where some E_e == 0 (the centre lies exactly on the
// edge), that edge is a top edge (horizontal, with the triangle below it, i.e. running in +x)
// or a left edge (running in -y). Two triangles sharing an edge evaluate it with exactly
// opposite signs, and exactly one of the two directions is top-left, so a centre on the edge is
// covered by exactly one of them: no cracks, no double coverage. Bit y * 8 + x of a tile's mask
// is pixel (8 tx + x, 8 ty + y); bits of pixels outside the image are 0.
//
// Clipping and guard band. Triangles are clipped homogeneously (Sutherland-Hodgman in clip
// space, intersection points always computed from the inside end of an edge, so triangles that
// share an edge get the same points) against the near plane and against a guard band 2^19 pixels
// beyond each image border. The clipped polygon (at most 8 corners) is split into a fan of at
// most 6 pieces that share their internal edges exactly. The far plane is not clipped: depth is
// not the rasterizer's business. Image sides are at most 2^16, so snapped coordinates satisfy
// |X| < 2^28, edge-function products < 2^58 and edge values < 2^59: int64 never overflows.
//
// Stats (RasterStats): triangles_in = triangles_culled + triangles_rasterized.
//   triangles_culled: source triangles with nothing left to rasterize, by reason: culled_behind
//     (entirely behind the near plane), culled_offscreen (no pixel centre of the image inside
//     the bounding box, or entirely outside the guard band), culled_degenerate (zero area after
//     snapping: collinear or repeated corners, or too small), culled_invalid (index out of range,
//     non-finite coordinates, w <= 0 in front of the near plane).
//   triangles_clipped (of the rasterized ones): cut by the near plane (clipped_near) or the guard
//     band (clipped_guard); pieces: rasterizable triangles after clipping (records set up).
//   entries_needed: (mask, triangle) pairs with a non-zero mask; entries: pairs stored;
//   max_entries_per_tile: the most pairs any tile needed.
//   overflow: entries_needed exceeded RasterOptions::max_entries (taken as at most 2^32 - 1).
//     Lists are then complete for tiles [0, first_incomplete_tile) and empty from there on
//     (dropped_tiles of them needed entries); nothing is written beyond the stored entries.
// A tile's entries are sorted by (triangle, mask), so the lists are identical on every backend.
// A clipped triangle's pieces may give it more than one entry in a tile (with disjoint masks).
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/hd.h"
#include "cuda/buffer.h"
#include "cuda/execute.h"
#include "engine/raster/raster_projection.h"
#include "engine/raster/triangle_setup.h"
#include "engine/scene/scene_view.h"

namespace dv {

// Where the triangles land: the projection plus the triangles (in the backend's memory).
struct RasterView {
  RasterProjection projection;
  View<const dvec3> vertices;
  View<const u32vec3> triangles;
};

inline RasterView make_raster_view(const SceneView& scene, const RasterProjection& projection) {
  return {projection, scene.vertices, scene.triangles};
}

struct TileEntry {
  uint64_t mask;      // covered pixel centres of the tile, bit y * 8 + x
  uint32_t triangle;  // source triangle index (into RasterView::triangles)
  uint32_t reserved;  // 0
};

struct TileListsView {
  int width, height, tiles_x, tiles_y;
  View<const uint32_t> offsets;  // tiles + 1: tile t's entries are [offsets[t], offsets[t + 1])
  View<const TileEntry> entries;
};

// Tiles along a side of `pixels` pixels (the last one partial where it does not divide).
DV_HD inline int tiles_along(int pixels) {
  return (pixels + kTileSide - 1) / kTileSide;
}

// Threads that shade a width x height view tile by tile: kTileSide^2 per raster tile, the
// threads of tiles sticking out of the view included.
DV_HD inline int64_t tiled_thread_count(int width, int height) {
  return int64_t(tiles_along(width)) * tiles_along(height) * kTileSide * kTileSide;
}

// The pixel of thread i of tiled_thread_count's threads (the tiles row by row, each tile's
// pixels row by row): the 32 lanes of a warp take half a tile, so their rays lie close together,
// read the same fragment list and march through the same volume cells, where a warp over 32
// pixels of one row spans four tiles. False for the threads outside the view.
DV_HD inline bool pixel_of_tiled_thread(int64_t i, int width, int height, int& x, int& y) {
  const int64_t tile = i / (kTileSide * kTileSide);
  const int local = int(i % (kTileSide * kTileSide));
  const int tiles_x = tiles_along(width);
  x = int(tile % tiles_x) * kTileSide + local % kTileSide;
  y = int(tile / tiles_x) * kTileSide + local / kTileSide;
  return x < width && y < height;
}

DV_HD inline int64_t tile_of_pixel(const TileListsView& v, int x, int y) {
  return int64_t(y / kTileSide) * v.tiles_x + x / kTileSide;
}

DV_HD inline uint64_t pixel_bit(int x, int y) {
  return uint64_t(1) << ((y % kTileSide) * kTileSide + x % kTileSide);
}

// Calls visit(triangle) for every entry of pixel (x, y)'s tile that covers the pixel centre,
// in increasing triangle order. (x, y) must be inside the image.
template <class Visit>
DV_HD void for_each_fragment(const TileListsView& v, int x, int y, Visit&& visit) {
  const int64_t tile = tile_of_pixel(v, x, y);
  const uint64_t bit = pixel_bit(x, y);
  const uint32_t end = v.offsets[tile + 1];
  for (uint32_t k = v.offsets[tile]; k < end; ++k)
    if (v.entries[k].mask & bit) visit(v.entries[k].triangle);
}

DV_HD inline int fragment_count(const TileListsView& v, int x, int y) {
  int count = 0;
  for_each_fragment(v, x, y, [&count](uint32_t) { ++count; });
  return count;
}

struct RasterStats {
  int64_t triangles_in = 0;
  int64_t triangles_rasterized = 0;
  int64_t triangles_clipped = 0;
  int64_t clipped_near = 0;
  int64_t clipped_guard = 0;
  int64_t triangles_culled = 0;
  int64_t culled_behind = 0;
  int64_t culled_offscreen = 0;
  int64_t culled_degenerate = 0;
  int64_t culled_invalid = 0;
  int64_t pieces = 0;
  int64_t entries = 0;
  int64_t entries_needed = 0;
  int64_t max_entries_per_tile = 0;
  bool overflow = false;
  int64_t first_incomplete_tile = 0;  // tile count when nothing overflowed
  int64_t dropped_tiles = 0;
};

void to_json(nlohmann::json& out, const RasterStats& stats);

// The buffers of tile lists binned over one image size: tile t's entries (of every projection,
// projection p's tiles after p - 1's) are entries[offsets[t], offsets[t + 1]).
struct TileListBuffers {
  int width = 0, height = 0, tiles_x = 0, tiles_y = 0;
  Buffer<uint32_t> offsets;  // projections * tile_count() + 1, into entries
  Buffer<TileEntry> entries;

  int64_t tile_count() const { return int64_t(tiles_x) * tiles_y; }  // per projection
  TileListsView view(int projection = 0) const;                      // one projection's lists
  TileListBuffers to_host() const;                                   // a copy in host memory
};

// The tile lists of one projection (rasterize_tiles).
struct TileLists : TileListBuffers {
  RasterStats stats;

  TileLists to_host() const;
};

// The tile lists of several projections of one image size over the same triangles, binned
// together (rasterize_tile_set): projection p's lists, view(p), equal rasterize_tiles' lists of
// p alone.
struct TileListSet : TileListBuffers {
  std::vector<RasterStats> stats;  // per projection

  int projections() const { return int(stats.size()); }
};

struct RasterOptions {
  // Most (mask, triangle) pairs stored; more sets the overflow flag (at most 2^32 - 1). A set
  // of projections shares the limit: its lists are complete up to the first tile, in
  // projection order, whose list does not fit.
  int64_t max_entries = 2147483647;
};

// Bins the view's triangles into tile lists. The triangles and vertices must be in the
// backend's memory; the lists come back in the same memory.
TileLists rasterize_tiles(Backend backend, const RasterView& view,
                          const RasterOptions& options = {});
TileLists rasterize_tiles(Backend backend, const SceneView& scene,
                          const RasterProjection& projection, const RasterOptions& options = {});

// Bins the triangles under every projection (all of one image size) in one run of the
// passes over every (projection, triangle) pair, so the many light faces of a scene pay the
// passes' launches and read-backs once instead of once a face (112 faces of 32 lights: 112
// runs before). Records take 81 bytes a pair while it runs: callers split long lists of
// projections (tile_set_projections).
TileListSet rasterize_tile_set(Backend backend, View<const dvec3> vertices,
                               View<const u32vec3> triangles,
                               const std::vector<RasterProjection>& projections,
                               const RasterOptions& options = {});

// How many projections one rasterize_tile_set call should take for `triangles` triangles: at
// least 1, and at most as many as keep the pairs within 2^22 (about 340 MB of records).
int tile_set_projections(int64_t triangles);

// Fragments (covering triangles) per pixel, row-major, in the lists' memory.
Buffer<uint32_t> count_pixel_fragments(Backend backend, const TileLists& lists);

}  // namespace dv
