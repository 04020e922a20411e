// The camera pass's tile order (see fragment_lanes.h): a flag and a cost key per tile, the flags'
// exclusive scan (the count of volume tiles), and a stable sort of the tiles by decreasing key.
#include "frame/fragment_lanes.h"

#include "cuda/scan.h"
#include "cuda/sort.h"
#include "renderer/media_march.h"

namespace dv {

int64_t FragmentOrder::volume_tiles() const {
  return starts.to_vector()[size_t(order.size())];
}

FragmentOrder order_fragment_tiles(Backend backend, const SceneView& s,
                                   const RasterProjection& projection, const TileListsView lists,
                                   const InsideSet* eye_media) {
  const Memory memory = memory_of(backend);
  const int64_t tiles = int64_t(lists.tiles_x) * lists.tiles_y;
  FragmentOrder result{Buffer<int32_t>(memory, tiles, "fragment tile order"),
                       Buffer<int64_t>(memory, tiles + 1, "fragment volume tile starts")};
  Buffer<uint32_t> cost(memory, tiles, "fragment tile cost");
  Buffer<int32_t> tile_index(memory, tiles, "fragment tile index");
  const View<int64_t> flag = result.starts.view();
  const View<uint32_t> key = cost.view();
  const View<int32_t> index = tile_index.view();
  const int tiles_x = lists.tiles_x;
  parallel_for(
      backend, "raster_volume_tiles", tiles + 1, DV_KERNEL_LAMBDA(int64_t t) {
        if (t == tiles) {
          flag[t] = 0;
          return;
        }
        bool volume = has_volume(s, *eye_media);
        for (uint32_t k = lists.offsets[t]; !volume && k < lists.offsets[t + 1]; ++k)
          volume = s.objects[s.triangle_object[lists.entries[k].triangle]].interior ==
                   InteriorKind::volume;
        flag[t] = volume ? 1 : 0;
        key[t] = volume ? volume_tile_cost(s, projection, t, tiles_x) : 0;
        index[t] = int32_t(t);
      });
  exclusive_scan_queued(backend, flag);
  sort_by_key_descending_queued(backend, cost.const_view(), tile_index.const_view(),
                                result.order.view(), int(kTileCostBits));
  return result;
}

}  // namespace dv
