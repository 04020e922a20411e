// Host side of deep-shadow-map generation that does not depend on the storage strategy: the
// faces of every light (engine/raster/light_faces.h; fitted to the casters only, never to a
// camera, so a camera move never forces regeneration) or the clusters' faces with the objects
// each sees (engine/dsm/light_clusters.h), the tile lists of each face from the shared
// rasterizer, the media containing each face's ray origins, and the per-texel records.
// Storage strategies run their passes over DsmGeneration::generator() (engine/dsm/dsm_generator.h).
#pragma once

#include <vector>

#include "cuda/buffer.h"
#include "cuda/execute.h"
#include "engine/dsm/dsm_generator.h"
#include "engine/dsm/light_clusters.h"
#include "engine/raster/light_faces.h"
#include "engine/raster/tile_raster.h"
#include "engine/scene/scene_view.h"

namespace dv {

struct DsmGenerationOptions {
  int resolution = 512;
  int subrays = 1;  // 4, 9 or 16: pre-filtered texels (engine/dsm/prefilter.h)
  bool precompressed =
      false;            // volume steps from Hadwiger's tables (engine/dsm/precompressed_table.h)
  int table_bins = 64;  // density bins per axis of those tables
  float table_eps = 0.005f;  // their compression bound per step
  double step_scale = 1.0;   // multiplies the volumes' steps (accuracy studies)
  int light = -1;            // >= 0: only this light's faces (mapped_lights, light_faces.h)
};

class DsmGeneration {
 public:
  // Rasterizes every face of every light (options.light >= 0: of that light alone), faces of one
  // size together (rasterize_tile_set); throws if a tile list overflows. With `clusters` the faces
  // are the clusters' (at clusters->resolution, each seeing only its cluster's objects) instead of
  // the standard faces at options.resolution.
  DsmGeneration(const SceneData& scene, Backend backend, const DsmGenerationOptions& options,
                const ClusteredLayout* clusters = nullptr);

  const DsmGenerator& generator() const { return generator_; }
  const LightMapLayout& layout() const { return layout_; }
  View<const ShadowFace> faces() const { return faces_.const_view(); }
  View<const ShadowLight> lights() const { return lights_.const_view(); }
  Backend backend() const { return backend_; }
  double raster_milliseconds() const { return raster_ms_; }
  double table_milliseconds() const { return table_ms_; }  // pre-compressed tables' build
  int64_t fragments() const;                               // tile-list entries over all faces

 private:
  Backend backend_;
  LightMapLayout layout_;
  Buffer<ShadowFace> faces_;
  Buffer<ShadowLight> lights_;
  std::vector<TileListSet> sets_;  // the faces' tile lists, faces of one size binned together
  Buffer<TileListsView> list_views_;
  Buffer<InsideSet> ray_media_;
  Buffer<uint32_t> object_masks_;
  Buffer<PrecompressedStep> table_steps_;
  Buffer<int32_t> object_table_;
  Buffer<dvec2> table_domain_;
  DsmGenerator generator_;
  double raster_ms_ = 0.0;
  double table_ms_ = 0.0;
};

}  // namespace dv
