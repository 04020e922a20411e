// visible_surface: one closest-hit BVH query per pixel (see visible_surface.h).
#include "engine/raster/visible_surface.h"

#include "cuda/buffer.h"
#include "engine/raster/raster_projection.h"
#include "engine/scene/ray_query.h"
#include "engine/scene/texture_sampling.h"

namespace dv {

namespace {

struct PixelSurface {
  dvec3 point;
  uint32_t hit;
};

// Keeps the nearest hit on a visible surface (alpha > 0 at the hit) in front of the near plane;
// lowers the traversal's t_max to it so that farther nodes are skipped.
struct NearestVisibleHit {
  const SceneView* scene;
  const RasterProjection* projection;
  const PixelRay* ray;
  double* t_max;
  bool* found;

  DV_HD bool operator()(const RayHit& h) const {
    if (!(h.t > 0.0 && h.t <= *t_max)) return true;
    const dvec3 p = ray->origin + ray->direction * h.t;
    if (!(surface_alpha(*scene, h.triangle, p) > 0.0)) return true;
    if (near_plane_distance(*projection, world_to_clip_point(*projection, p)) < 0.0) return true;
    *t_max = h.t;
    *found = true;
    return true;
  }
};

}  // namespace

VisibleSurface visible_surface(Backend backend, const SceneData& scene, const Camera& camera) {
  const Memory memory = memory_of(backend);
  if (scene.memory() != memory) throw Error("visible_surface: scene data is in the wrong memory");
  const SceneView view = scene.view();
  const RasterProjection projection = make_camera_projection(camera, view.bounds);
  const int width = projection.width;
  Buffer<PixelSurface> out(memory, int64_t(width) * projection.height, "visible surface");
  const View<PixelSurface> pixels = out.view();
  parallel_for(
      backend, "visible_surface", pixels.size, DV_KERNEL_LAMBDA(int64_t i) {
        const PixelRay ray = pixel_ray(projection, int(i % width), int(i / width));
        const ShearedRay sheared = make_sheared_ray(ray.origin, ray.direction);
        double t_max = INFINITY;
        bool found = false;
        traverse_bvh(view, sheared, 0.0, t_max,
                     NearestVisibleHit{&view, &projection, &ray, &t_max, &found});
        pixels[i] = {ray.origin + ray.direction * t_max, found ? 1u : 0u};
      });
  VisibleSurface result;
  result.width = width;
  result.height = projection.height;
  for (const PixelSurface& p : out.to_vector()) {
    result.points.push_back(p.hit ? p.point : dvec3(0.0));
    result.hit.push_back(uint8_t(p.hit));
  }
  return result;
}

}  // namespace dv
