// Crossings of a pixel's ray taken from the rasterizer's tile lists: the triangles whose
// coverage mask holds the pixel centre, each at the exact depth where the pixel ray meets its
// plane, served in (depth, triangle) order. The fragment source of the rasterizing renderer
// (renderer/fragment_walk.h). Host and device code.
#pragma once

#include "core/hd.h"
#include "renderer/raster/tile_raster.h"
#include "scene/ray_query.h"
#include "scene/scene_view.h"

namespace dv {

struct RasterFragments {
  const SceneView* scene;
  TileListsView lists;
  int x, y;
  dvec3 origin;
  dvec3 dir;

  DV_HD bool next(double t_after, int64_t after_triangle, RayHit& out) const {
    bool found = false;
    for_each_fragment(lists, x, y, [&](uint32_t tri) {
      double t;
      bool entering;
      if (!triangle_plane_hit(*scene, tri, origin, dir, t, entering)) return;  // seen edge-on
      const bool after = t > t_after || (t == t_after && int64_t(tri) > after_triangle);
      if (after && (!found || t < out.t || (t == out.t && tri < out.triangle))) {
        out = RayHit{t, tri, entering};
        found = true;
      }
    });
    return found;
  }
};

}  // namespace dv
