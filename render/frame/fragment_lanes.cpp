// The camera pass's tile order (see fragment_lanes.h): a cost key per tile (0 for the tiles
// without a volume crossing), the count of the volume tiles, and a stable sort of the tiles by
// decreasing key.
#include "render/frame/fragment_lanes.h"

#include "core/atomic.h"
#include "cuda/sort.h"
#include "engine/raster/media_march.h"

namespace dv {

int64_t FragmentOrder::volume_tiles() const {
  return int64_t(volume_tile_count.to_vector()[0]);
}

FragmentOrder order_fragment_tiles(Backend backend, const SceneView& s,
                                   const RasterProjection& projection, const TileListsView lists,
                                   const InsideSet* eye_media) {
  const Memory memory = memory_of(backend);
  const int64_t tiles = int64_t(lists.tiles_x) * lists.tiles_y;
  FragmentOrder result{Buffer<int32_t>(memory, tiles, "fragment tile order"),
                       Buffer<unsigned long long>(memory, 1, "fragment volume tiles")};
  Buffer<uint32_t> cost(memory, tiles, "fragment tile cost");
  Buffer<uint32_t> volume_flag(memory, tiles, "fragment volume tile flags");
  Buffer<int32_t> tile_index(memory, tiles, "fragment tile index");
  const View<uint32_t> key = cost.view(), flag = volume_flag.view();
  const View<int32_t> index = tile_index.view();
  unsigned long long* const count = result.volume_tile_count.data();
  parallel_for(
      backend, "raster_tile_order_clear", tiles, DV_KERNEL_LAMBDA(int64_t t) {
        key[t] = 0;
        flag[t] = 0;
        index[t] = int32_t(t);
        if (t == 0) *count = 0;
      });
  // kListLanes threads read a tile's list, each every kListLanes-th entry (a list can hold
  // hundreds, each a chain of three dependent loads); the first to find a volume crossing counts
  // the tile.
  constexpr int kListLanes = 32;
  parallel_for(
      backend, "raster_volume_tiles", tiles * kListLanes, DV_KERNEL_LAMBDA(int64_t i) {
        const int64_t t = i / kListLanes;
        const int lane = int(i % kListLanes);
        bool volume = lane == 0 && has_volume(s, *eye_media);
        for (uint32_t k = lists.offsets[t] + lane; !volume && k < lists.offsets[t + 1];
             k += kListLanes)
          volume = s.objects[s.triangle_object[lists.entries[k].triangle]].interior ==
                   InteriorKind::volume;
        if (volume && atomic_max(&flag[t], 1u) == 0) atomic_add(count, 1ull);
      });
  // The probes of a tile in parallel: each is a chain of dependent brick steps.
  parallel_for(
      backend, "raster_volume_tile_cost", tiles * kTileProbes, DV_KERNEL_LAMBDA(int64_t i) {
        const int64_t t = i / kTileProbes;
        if (flag[t] != 0)
          atomic_max(&key[t], tile_probe_cost(s, projection, t, int(i % kTileProbes)));
      });
  sort_by_key_descending_queued(backend, cost.const_view(), tile_index.const_view(),
                                result.order.view(), int(kTileCostBits));
  return result;
}

}  // namespace dv
