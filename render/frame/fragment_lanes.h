// How many threads the camera pass gives each pixel, and the order of the tiles. The pass's time
// is that of its slowest warps, those of the pixels with the most volume steps: there a warp's
// step is thousands of cycles of dependent double-precision work, and the few such warps leave
// most of the GPU idle while they run (a per-warp timeline of knecht-fig56's pass showed its
// slowest warps running for nearly the whole pass, with few of its warps left after the first
// third; results/perf/rounds/07-fragment-lanes). So the tiles
// whose lists hold a crossing of a volume's boundary (all of them when the eye is inside a
// volume) give each pixel kVolumeLanes lanes that split its volume steps between them
// (render/frame/shade_payload.h), and they go first, heaviest first: more of their warps are ready
// than the GPU runs at once, and taken in tile order the heaviest of them started late, a third
// of the way into the pass (the same timeline with lanes). Heaviest first shortens the pass by
// more than the ordering costs, with or without a shadow map
// (results/perf/rounds/08-heaviest-tiles-first has the times). The other tiles keep one thread per
// pixel.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "core/lane_group.h"
#include "core/math.h"
#include "cuda/buffer.h"
#include "engine/raster/fragment_walk.h"
#include "engine/raster/raster_projection.h"
#include "engine/raster/tile_raster.h"
#include "engine/scene/volume_sampling.h"

namespace dv {

// The key of a volume tile in the order: of kTileProbes probe rays (the tile's corner pixels and
// its centre), the most volume samples one would take, counted as the length it runs in bricks
// that are not empty over each volume's step (occluders and saturation ignored), plus one, so
// that a volume tile's key is never 0 (the other tiles' key); at most kMostTileCost.
inline constexpr int kTileProbes = 5;
inline constexpr uint32_t kTileCostBits = 20;
inline constexpr uint32_t kMostTileCost = (uint32_t(1) << kTileCostBits) - 1;

// Probe `probe` of the tile's key (0-3 the corners, row by row; 4 the centre): its samples plus
// one.
DV_HD inline uint32_t tile_probe_cost(const SceneView& s, const RasterProjection& projection,
                                      int64_t tile, int probe) {
  int x0, y0;  // the tile's first pixel, always in the view
  pixel_of_tiled_thread(tile * kTileSide * kTileSide, projection.width, projection.height, x0, y0);
  const int x_last = min_value(x0 + kTileSide - 1, projection.width - 1);
  const int y_last = min_value(y0 + kTileSide - 1, projection.height - 1);
  const bool centre = probe == kTileProbes - 1;
  const int x = centre ? (x0 + x_last) / 2 : probe % 2 ? x_last : x0;
  const int y = centre ? (y0 + y_last) / 2 : probe / 2 ? y_last : y0;
  const PixelRay ray = pixel_ray(projection, x, y);
  double samples = 0.0;
  for (int64_t k = 0; k < s.objects.size; ++k) {
    const ObjectView& o = s.objects[k];
    if (o.interior == InteriorKind::volume)
      samples += occupied_brick_length(s, o, ray.origin, ray.direction, 0.0) / o.step;
  }
  const double most = double(kMostTileCost - 1);
  return uint32_t(samples < most ? samples : most) + 1;  // a NaN counts as the most
}

DV_HD inline uint32_t volume_tile_cost(const SceneView& s, const RasterProjection& projection,
                                       int64_t tile) {
  uint32_t most = 0;
  for (int p = 0; p < kTileProbes; ++p)
    most = max_value(most, tile_probe_cost(s, projection, tile, p));
  return most;
}

// Lanes per pixel in volume tiles: 2 measured best of 2, 4 and 8 on knecht-fig56 (one light;
// more lanes repeat more of each pixel's walk and surface shading than they save), 4 on
// knecht-planner (seven lights), where 2 still shortens the fragment pass by almost a third.
inline constexpr int kVolumeLanes = 2;

// The tiles in the pass's order, as the pass's threads read it.
struct FragmentOrderView {
  View<const int32_t> order;  // the tiles, those with volume crossings first, heaviest first
  const unsigned long long* volume_tiles;  // how many of those there are (in the order's memory)
};

// The pass's threads: kVolumeLanes per pixel of every tile, as many as a view of volume tiles
// only would need; the threads past the last tile return at once.
DV_HD inline int64_t fragment_thread_count(int64_t tiles) {
  return tiles * kTileSide * kTileSide * kVolumeLanes;
}

// The pixel and lane group of thread i of the pass: the volume tiles' threads first, a warp
// taking 32 / kVolumeLanes pixels of one tile with each group of kVolumeLanes consecutive lanes
// on one pixel, then the other tiles' threads, one per pixel; within a tile the pixels in
// pixel_of_tiled_thread's order. False past the last tile and for pixels outside the view.
DV_HD inline bool pixel_of_fragment_thread(int64_t i, const FragmentOrderView& o, int width,
                                           int height, int& x, int& y, LaneGroup& group) {
  constexpr int64_t kPixels = kTileSide * kTileSide;
  const int64_t shared = int64_t(*o.volume_tiles), shared_threads = shared * kPixels * kVolumeLanes;
  const bool in_shared = i < shared_threads;
  const int lanes = in_shared ? kVolumeLanes : 1;
  const int64_t offset = in_shared ? i : i - shared_threads;
  const int64_t rank = (in_shared ? 0 : shared) + offset / (kPixels * lanes);
  const int thread = int(offset % (kPixels * lanes));
  group = LaneGroup{thread % lanes, lanes};
  if (rank >= o.order.size) return false;
  return pixel_of_tiled_thread(int64_t(o.order[rank]) * kPixels + thread / lanes, width, height, x,
                               y);
}

struct FragmentOrder {
  Buffer<int32_t> order;
  Buffer<unsigned long long> volume_tile_count;  // one value

  FragmentOrderView view() const { return {order.const_view(), volume_tile_count.data()}; }
  int64_t volume_tiles() const;  // a read-back
};

// Finds the volume tiles and orders the tiles, on the device (no read-back): the volume tiles
// by decreasing volume_tile_cost, then the others, each in tile order where their keys are equal.
FragmentOrder order_fragment_tiles(Backend backend, const SceneView& s,
                                   const RasterProjection& projection, const TileListsView lists,
                                   const InsideSet* eye_media);

}  // namespace dv
