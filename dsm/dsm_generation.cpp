// DsmGeneration (see dsm_generation.h). Compiled by nvcc when CUDA is on.
#include "dsm/dsm_generation.h"

#include <string>

#include "core/pass_timer.h"
#include "renderer/fragment_walk.h"

namespace dv {

DsmGeneration::DsmGeneration(const SceneData& scene, Backend backend, int res) : backend_(backend) {
  const SceneView& s = scene.view();
  layout_ = light_map_layout(scene.host_lights(), s.bounds, s.diagonal, res);
  const Memory memory = backend == Backend::cuda ? Memory::device : Memory::host;
  faces_ = Buffer<ShadowFace>(memory, layout_.faces, "dsm faces");
  lights_ = Buffer<ShadowLight>(memory, layout_.lights, "dsm lights");
  PassTimer timer(backend);
  std::vector<TileListsView> views;
  for (const ShadowFace& f : layout_.faces) {
    lists_.push_back(rasterize_tiles(backend, s, f.projection));
    if (lists_.back().stats.overflow)
      throw Error("dsm: tile lists overflowed while rasterizing a light's face (" +
                  std::to_string(lists_.back().stats.entries_needed) + " entries needed)");
    views.push_back(lists_.back().view());
  }
  list_views_ = Buffer<TileListsView>(memory, views, "dsm tile lists");
  ray_media_ = Buffer<InsideSet>(memory, int64_t(layout_.faces.size()), "dsm ray media");
  const View<const ShadowFace> faces = faces_.const_view();
  const View<InsideSet> media = ray_media_.view();
  parallel_for(
      backend, "dsm_ray_media", faces.size, DV_KERNEL_LAMBDA(int64_t i) {
        // Orthographic faces start on a near plane outside the casters' bounding sphere.
        media[i] = faces[i].orthographic ? InsideSet{} : media_containing(s, faces[i].eye).inside;
      });
  raster_ms_ = timer.stop();
  generator_.scene = s;
  generator_.faces = faces;
  generator_.lists = list_views_.const_view();
  generator_.ray_media = ray_media_.const_view();
  generator_.resolution = res;
  generator_.blocks_per_side = (res + kDsmBlockSide - 1) / kDsmBlockSide;
}

int64_t DsmGeneration::fragments() const {
  int64_t total = 0;
  for (const TileLists& l : lists_) total += l.stats.entries;
  return total;
}

}  // namespace dv
