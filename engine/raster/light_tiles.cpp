// Building the per-tile light masks (see light_tiles.h): one thread per (tile, word of 32
// lights) tests its lights against the tile's depth slices.
#include "engine/raster/light_tiles.h"

#include <cmath>
#include <string>
#include <vector>

#include "core/bits.h"
#include "core/error.h"
#include "cuda/execute.h"
#include "engine/oracle/transmittance.h"
#include "engine/raster/camera_rays.h"

namespace dv {

namespace {

// View depths (along the camera's forward axis) that the scene's bounds span, from the near
// plane on (at least a little above 0); lo > hi when the scene lies wholly in front of the near
// plane.
struct DepthRange {
  double lo;
  double hi;
};

DepthRange scene_depths(const SceneView& s, const CameraView& cam) {
  const Aabb box = padded_bounds(s);
  double z_lo = 1e300, z_hi = -1e300;
  for (int k = 0; k < 8; ++k) {
    const dvec3 corner(k & 1 ? box.hi.x : box.lo.x, k & 2 ? box.hi.y : box.lo.y,
                       k & 4 ? box.hi.z : box.lo.z);
    const double z = glm::dot(corner - cam.position, cam.forward);
    z_lo = min_value(z_lo, z);
    z_hi = max_value(z_hi, z);
  }
  return {max_value(z_lo, max_value(cam.near_plane, 1e-6 * s.diagonal + 1e-9)), z_hi};
}

}  // namespace

LightTiles build_light_tiles(Backend backend, const SceneView& scene, const Camera& camera,
                             const LightCulling& culling) {
  if (!(culling.cutoff >= 0.0) || !std::isfinite(culling.cutoff))
    throw Error("light culling: the cut-off must be a finite number >= 0, not " +
                std::to_string(culling.cutoff));
  LightTiles tiles;
  const int lights = int(scene.lights.size);
  if (lights == 0 || (lights == 1 && (culling.cutoff == 0.0 || !culling.enabled))) return tiles;
  tiles.tiles_x = (camera.width + kLightTilePixels - 1) / kLightTilePixels;
  tiles.tiles_y = (camera.height + kLightTilePixels - 1) / kLightTilePixels;
  tiles.words = (lights + 31) / 32;
  tiles.every_light = !culling.enabled;
  const int64_t count = int64_t(tiles.tiles_x) * tiles.tiles_y * tiles.words;
  tiles.masks = Buffer<uint32_t>(memory_of(backend), count, "light tile masks");
  const CameraView cam = make_camera_view(camera);
  const DepthRange depths = scene_depths(scene, cam);
  const View<uint32_t> masks = tiles.masks.view();
  const View<const LightView> light_views = scene.lights;
  const int tiles_x = tiles.tiles_x, words = tiles.words;
  const double cutoff = culling.cutoff;
  const bool cull = culling.enabled;
  const double slack = 1e-9 * (scene.diagonal + glm::length(cam.position)) + 1e-12;
  const Aabb scene_box = padded_bounds(scene);
  const dvec3 scene_lo = scene_box.lo, scene_hi = scene_box.hi;
  parallel_for(
      backend, "light_tiles", count, DV_KERNEL_LAMBDA(int64_t i) {
        const int64_t tile = i / words;
        const int word = int(i % words);
        if (!cull) {  // every light
          masks[i] = bits_below(~0u, int(light_views.size) - 32 * word);
          return;
        }
        uint32_t listed = 0;
        if (depths.lo <= depths.hi) {
          const int x0 = int(tile % tiles_x) * kLightTilePixels;
          const int y0 = int(tile / tiles_x) * kLightTilePixels;
          const int x1 = min_value(x0 + kLightTilePixels, cam.width);
          const int y1 = min_value(y0 + kLightTilePixels, cam.height);
          // The tile's image rectangle in camera_ray_direction's coordinates.
          const double sx[2] = {double(x0) / cam.width * 2.0 - 1.0,
                                double(x1) / cam.width * 2.0 - 1.0};
          const double sy[2] = {1.0 - double(y1) / cam.height * 2.0,
                                1.0 - double(y0) / cam.height * 2.0};
          const double ratio = depths.hi / depths.lo;
          for (int b = 0; b < 32; ++b) {
            const int li = word * 32 + b;
            if (li >= int(light_views.size)) break;
            const LightView& l = light_views[li];
            const double reach = light_reach(l, cutoff);
            for (int k = 0; k < kLightTileSlices; ++k) {
              // Depth slice k of kLightTileSlices, spaced geometrically (the last ends at hi).
              // The first starts at the eye.
              const double z0 = k == 0 ? 0.0 : depths.lo * pow(ratio, double(k) / kLightTileSlices);
              const double z1 = k + 1 == kLightTileSlices
                                    ? depths.hi
                                    : depths.lo * pow(ratio, double(k + 1) / kLightTileSlices);
              // The slice's box, cut to the scene's: its ball holds every point shaded there.
              dvec3 lo(1e300), hi(-1e300);
              for (int c = 0; c < 8; ++c) {
                const double z = c & 4 ? z1 : z0;
                const dvec3 p = cam.position + z * (cam.forward + sx[c & 1] * cam.right +
                                                    sy[(c >> 1) & 1] * cam.up);
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
              }
              lo = glm::max(lo, scene_lo);
              hi = glm::min(hi, scene_hi);
              if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z) continue;
              const dvec3 centre = 0.5 * (lo + hi);
              const double radius = 0.5 * glm::length(hi - lo);
              if (light_may_reach_ball(l, reach, centre, radius * (1.0 + 1e-9) + slack)) {
                listed |= 1u << b;
                break;
              }
            }
          }
        }
        masks[i] = listed;
      });
  return tiles;
}

ListedLights count_listed_lights(const LightTiles& tiles, int width, int height, int lights) {
  const unsigned long long pixels = (unsigned long long)(width) * (unsigned long long)(height);
  if (!tiles.culled())
    return {pixels * (unsigned long long)(lights), pixels ? (unsigned long long)(lights) : 0ull};
  const std::vector<uint32_t> masks = tiles.masks.to_vector();
  ListedLights out;
  for (int ty = 0; ty < tiles.tiles_y; ++ty)
    for (int tx = 0; tx < tiles.tiles_x; ++tx) {
      unsigned long long listed = 0;
      const size_t first = (size_t(ty) * tiles.tiles_x + tx) * tiles.words;
      for (int w = 0; w < tiles.words; ++w) listed += bit_count(masks[first + w]);
      const int w = min_value(kLightTilePixels, width - tx * kLightTilePixels);
      const int h = min_value(kLightTilePixels, height - ty * kLightTilePixels);
      out.sum += listed * (unsigned long long)(w) * (unsigned long long)(h);
      out.max = max_value(out.max, listed);
    }
  return out;
}

}  // namespace dv
