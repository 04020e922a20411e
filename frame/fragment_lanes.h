// How many threads the camera pass gives each pixel, and the order of the tiles. The pass's time
// is that of its slowest warps, those of the pixels with the most volume steps: there a warp's
// step is thousands of cycles of dependent double-precision work, and the few such warps leave
// most of the GPU idle while they run (a per-warp timeline of knecht-fig56's 0.93 ms pass on the
// H200: its slowest warps ran for 0.85-0.89 ms, and after the first 0.3 ms fewer than 450 of its
// 10,800 warps were left running; results/2026-12-03-lanes-h200). So the tiles
// whose lists hold a crossing of a volume's boundary (all of them when the eye is inside a
// volume) give each pixel kVolumeLanes lanes that split its volume steps between them
// (frame/shade_payload.h), and they go first, heaviest first: more of their warps are ready
// than the GPU runs at once, and taken in tile order the heaviest of them started up to 0.24 ms
// into the 0.73 ms pass (the same timeline with lanes). The other tiles keep one thread per pixel.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "core/lane_group.h"
#include "core/math.h"
#include "cuda/buffer.h"
#include "renderer/fragment_walk.h"
#include "renderer/raster/raster_projection.h"
#include "renderer/raster/tile_raster.h"
#include "scene/volume_sampling.h"

namespace dv {

// The key of a volume tile in the order: of five probe rays (the tile's corner pixels and its
// centre), the most volume samples one would take, counted as the length it runs in bricks that
// are not empty over each volume's step (occluders and saturation ignored), plus one, so that a
// volume tile's key is never 0 (the other tiles' key); at most kMostTileCost.
inline constexpr uint32_t kTileCostBits = 20;
inline constexpr uint32_t kMostTileCost = (uint32_t(1) << kTileCostBits) - 1;

DV_HD inline uint32_t volume_tile_cost(const SceneView& s, const RasterProjection& projection,
                                       int64_t tile, int tiles_x) {
  const int x0 = int(tile % tiles_x) * kTileSide, y0 = int(tile / tiles_x) * kTileSide;
  const int x_last = min_value(x0 + kTileSide - 1, projection.width - 1);
  const int y_last = min_value(y0 + kTileSide - 1, projection.height - 1);
  const int probe_x[5] = {x0, x_last, x0, x_last, (x0 + x_last) / 2};
  const int probe_y[5] = {y0, y0, y_last, y_last, (y0 + y_last) / 2};
  double most = 0.0;
  for (int p = 0; p < 5; ++p) {
    const PixelRay ray = pixel_ray(projection, probe_x[p], probe_y[p]);
    double samples = 0.0;
    for (int64_t k = 0; k < s.objects.size; ++k) {
      const ObjectView& o = s.objects[k];
      if (o.interior == InteriorKind::volume)
        samples += occupied_brick_length(s, o, ray.origin, ray.direction, 0.0) / o.step;
    }
    most = max_value(most, samples);
  }
  return uint32_t(min_value(most, double(kMostTileCost - 1))) + 1;
}

// Lanes per pixel in volume tiles: 2 measured best of 2, 4 and 8 on knecht-fig56 (one light;
// more lanes repeat more of each pixel's walk and surface shading than they save), 4 on
// knecht-planner (seven lights), where 2 still takes the fragment pass from 1.26 to 0.87 ms.
inline constexpr int kVolumeLanes = 2;

// The tiles in the pass's order, as the pass's threads read it.
struct FragmentOrderView {
  View<const int32_t> order;    // the tiles, those with volume crossings first
  const int64_t* volume_tiles;  // how many of those there are (in the order's memory)
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
  const int64_t shared = *o.volume_tiles, shared_threads = shared * kPixels * kVolumeLanes;
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
  Buffer<int64_t> starts;  // tiles + 1: volume tiles before each tile; the last: their count

  FragmentOrderView view() const { return {order.const_view(), starts.data() + order.size()}; }
  int64_t volume_tiles() const;  // a read-back
};

// Finds the volume tiles and orders the tiles, on the device (no read-back): the volume tiles
// by decreasing volume_tile_cost, then the others, each in tile order where their keys are equal.
FragmentOrder order_fragment_tiles(Backend backend, const SceneView& s,
                                   const RasterProjection& projection, const TileListsView lists,
                                   const InsideSet* eye_media);

}  // namespace dv
