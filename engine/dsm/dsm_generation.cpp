// DsmGeneration (see dsm_generation.h). Compiled by nvcc when CUDA is on.
#include "engine/dsm/dsm_generation.h"

#include <string>

#include "cuda/pass_timer.h"
#include "engine/dsm/precompressed_table.h"
#include "engine/raster/fitted_light_faces.h"
#include "engine/raster/fragment_walk.h"
#include "engine/raster/tile_list_sets.h"

namespace dv {

namespace {

// The media containing each face's ray origins. Orthographic faces start on a near plane
// outside the casters' bounding sphere.
void find_ray_media(Backend backend, const SceneView& s, View<const ShadowFace> faces,
                    View<InsideSet> media) {
  parallel_for(
      backend, "dsm_ray_media", faces.size, DV_KERNEL_LAMBDA(int64_t i) {
        media[i] = faces[i].orthographic ? InsideSet{} : media_containing(s, faces[i].eye).inside;
      });
}

}  // namespace

DsmGeneration::DsmGeneration(const SceneData& scene, Backend backend,
                             const DsmGenerationOptions& options, const ClusteredLayout* clusters)
    : backend_(backend) {
  const int res = clusters ? clusters->resolution : options.resolution;
  const SceneView& s = scene.view();
  layout_ = clusters
                ? clusters->layout
                : fitted_light_map_layout(mapped_lights(scene.host_lights(), options.light),
                                          s.bounds, scene.host_object_bounds(), s.diagonal, res);
  const Memory memory = memory_of(backend);
  if (clusters) {
    object_masks_ = Buffer<uint32_t>(memory, clusters->object_masks, "dsm cluster object masks");
    generator_.object_masks = object_masks_.const_view();
    generator_.mask_words = clusters->mask_words;
  }
  faces_ = Buffer<ShadowFace>(memory, layout_.faces, "dsm faces");
  lights_ = Buffer<ShadowLight>(memory, layout_.lights, "dsm lights");
  PassTimer timer(backend);
  // The faces binned in sets (tile_list_sets.h): the rasterizer's passes once a set, not once a
  // face.
  std::vector<RasterProjection> projections;
  for (const ShadowFace& f : layout_.faces) projections.push_back(f.projection);
  sets_ = rasterize_tile_sets(backend, s.vertices, s.triangles, projections);
  std::vector<TileListsView> views;
  for (const TileListSet& set : sets_)
    for (int p = 0; p < set.projections(); ++p) {
      const RasterStats& stats = set.stats[size_t(p)];
      if (stats.overflow)
        throw Error("dsm: tile lists overflowed while rasterizing a light's face (" +
                    std::to_string(stats.entries_needed) + " entries needed)");
      views.push_back(set.view(p));
    }
  list_views_ = Buffer<TileListsView>(memory, views, "dsm tile lists");
  ray_media_ = Buffer<InsideSet>(memory, int64_t(layout_.faces.size()), "dsm ray media");
  const View<const ShadowFace> faces = faces_.const_view();
  find_ray_media(backend, s, faces, ray_media_.view());
  raster_ms_ = timer.stop();
  generator_.scene = s;
  generator_.faces = faces;
  generator_.lists = list_views_.const_view();
  generator_.ray_media = ray_media_.const_view();
  generator_.resolution = res;
  generator_.subrays = options.subrays;
  generator_.step_scale = options.step_scale;
  if (options.precompressed) {
    PassTimer table_timer(backend);
    const PrecompressedTableData t =
        build_precompressed_tables(scene, options.table_bins, options.table_eps);
    table_steps_ = Buffer<PrecompressedStep>(memory, t.steps, "dsm precompressed steps");
    object_table_ = Buffer<int32_t>(memory, t.object_table, "dsm precompressed table index");
    table_domain_ = Buffer<dvec2>(memory, t.domain, "dsm precompressed domains");
    generator_.tables = {table_steps_.const_view(), object_table_.const_view(),
                         table_domain_.const_view(), options.table_bins};
    table_ms_ = table_timer.stop();
  }
}

int64_t DsmGeneration::fragments() const {
  int64_t total = 0;
  for (const TileListSet& set : sets_)
    for (const RasterStats& stats : set.stats) total += stats.entries;
  return total;
}

}  // namespace dv
