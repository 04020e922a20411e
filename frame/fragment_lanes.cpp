// The camera pass's tile order (see fragment_lanes.h): a flag per tile, its exclusive scan, and a
// stable partition with the volume tiles first.
#include "frame/fragment_lanes.h"

#include "cuda/scan.h"
#include "renderer/media_march.h"

namespace dv {

int64_t FragmentOrder::volume_tiles() const {
  return starts.to_vector()[size_t(order.size())];
}

FragmentOrder order_fragment_tiles(Backend backend, const SceneView& s, const TileListsView lists,
                                   const InsideSet* eye_media) {
  const Memory memory = memory_of(backend);
  const int64_t tiles = int64_t(lists.tiles_x) * lists.tiles_y;
  FragmentOrder result{Buffer<int32_t>(memory, tiles, "fragment tile order"),
                       Buffer<int64_t>(memory, tiles + 1, "fragment volume tile starts")};
  const View<int64_t> flag = result.starts.view();
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
      });
  exclusive_scan_queued(backend, flag);
  const View<const int64_t> before = result.starts.const_view();
  const View<int32_t> order = result.order.view();
  parallel_for(
      backend, "raster_tile_order", tiles, DV_KERNEL_LAMBDA(int64_t t) {
        const int64_t volume_before = before[t], volume_tiles = before[tiles];
        const bool volume = before[t + 1] > volume_before;
        order[volume ? volume_before : volume_tiles + t - volume_before] = int32_t(t);
      });
  return result;
}

}  // namespace dv
