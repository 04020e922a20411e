// The reference renderer's pixel: a camera ray whose crossings come from the BVH, walked with
// the shading payload (see reference_render.h). Host and device code.
#pragma once

#include "core/atomic.h"
#include "core/hd.h"
#include "engine/oracle/transmittance.h"
#include "engine/raster/camera_rays.h"
#include "engine/raster/fragment_walk.h"
#include "render/frame/reference_render.h"
#include "render/frame/shade_payload.h"
#include "render/frame/walk_hooks.h"

namespace dv {

template <class Source>
DV_HD dvec3 walk_pixel(const SceneView& s, const CameraView& cam, const Source& shadows, int x,
                       int y, const uint32_t* light_mask, const dvec3& background,
                       RenderCounters* counters) {
  const dvec3 dir = camera_ray_direction(cam, x, y);
  // Start outside the scene so the media containing the eye are found by their crossings.
  const Aabb box = padded_bounds(s);
  double t_eye = 0.0;
  if (box.contains(cam.position))
    t_eye = max_value(box_exit_distance(box, cam.position, -dir), 0.0) + 1e-3 * s.diagonal + 1e-6;
  const dvec3 origin = cam.position - dir * t_eye;
  const double t_near = t_eye + cam.near_plane / glm::dot(dir, cam.forward);
  const double t_far = t_eye + max_value(box_exit_distance(box, cam.position, dir), 0.0);
  const int64_t thread = int64_t(y) * cam.width + x;
  ShadePayload<Source> payload{s, shadows, origin, dir};
  payload.cursor = first_cursor(shadows, thread);
  payload.light_mask = light_mask;
  const BvhFragments fragments{&s, make_sheared_ray(origin, dir)};
  const WalkStatus status = walk_fragments(s, fragments, InsideSet{}, 0.0, t_near, t_far, payload);
  finish_walk(shadows, payload.cursor, thread);
  if (counters && writes_pixels<Source>())
    count_pixel(counters, status.crossings, payload.samples, status.overflow, payload.cursor.flags);
  return payload.color + payload.transmittance * background;
}

}  // namespace dv
