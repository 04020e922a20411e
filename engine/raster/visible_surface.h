// The surface point each pixel of a camera sees: along the ray through the pixel centre (the
// rasterizer's, engine/raster/raster_projection.h), the nearest crossing of a surface with
// alpha > 0 in front of the near plane. Surfaces with alpha 0 (bare medium boundaries) are
// looked through; a pixel whose ray meets no visible surface has none. The viewer's error view
// asks the shadow methods about these points (strategies/shadow/probe.h). CPU threads or CUDA.
#pragma once

#include <vector>

#include "core/math.h"
#include "cuda/execute.h"
#include "engine/scene/scene.h"
#include "engine/scene/scene_view.h"

namespace dv {

struct VisibleSurface {
  std::vector<dvec3> points;  // per pixel, rows from the top; meaningful where `hit`
  std::vector<uint8_t> hit;   // per pixel: 1 when the ray meets a visible surface
  int width = 0, height = 0;
};

// `scene` must live in the memory of `backend`.
VisibleSurface visible_surface(Backend backend, const SceneData& scene, const Camera& camera);

}  // namespace dv
