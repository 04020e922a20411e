// Light culling per screen tile: for each tile of kLightTilePixels x kLightTilePixels
// pixels, the bit mask of the lights that can add to some point its pixels shade, so that the
// camera pass evaluates only those. A point a pixel shades lies on the pixel's ray, at a view
// depth between the near plane and the far side of the scene's bounds, inside those bounds; a
// tile's points lie in its frustum between those depths, cut into kLightTileSlices slices, each
// bounded by a sphere. A light is listed when it may reach some slice's sphere:
//   - a spot light only inside its cone (the sphere against the cone, exactly);
//   - a light with a glTF range only within the range;
//   - with cut-off c > 0, a point or spot light only within its reach sqrt(I * max(colour) / c),
//     beyond which its unshadowed irradiance I * max(colour) / d^2 is below c (a directional
//     light is dropped everywhere when I * max(colour) < c);
//   - a light of intensity <= 0 nowhere.
// With c = 0 (the default) only lights that add exactly nothing are dropped, and every pixel
// sums the same terms in the same order as without culling: the image is the same to the bit.
// With c > 0 a dropped light changes a pixel by less than c * (diffuse + specular) of the
// materials it lights (colours <= 1, the composite weights along a ray summing to <= 1).
// Lights stay in ascending index order within a mask. A scene with one light and c = 0 (or
// culling off) gets no masks: its pixels evaluate that light as before. With culling off and
// several lights every tile lists every light, so that the pass runs the loop over listed
// lights, the faster one for several lights (render/frame/shading.h).
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "core/math.h"
#include "cuda/buffer.h"
#include "engine/scene/scene.h"
#include "engine/scene/scene_view.h"

namespace dv {

inline constexpr int kLightTilePixels = 16;
inline constexpr int kLightTileSlices = 32;

struct LightCulling {
  bool enabled = true;
  double cutoff = 0.0;  // irradiance below which a light is dropped (>= 0; 0: exact culling)
};

// Distance beyond which light l adds nothing, or less than `cutoff` (1e300: no such distance;
// 0 for a light that adds nothing anywhere). Directional lights: 1e300 or 0.
DV_HD inline double light_reach(const LightView& l, double cutoff) {
  if (!(l.intensity > 0.0)) return 0.0;
  const double brightest = l.intensity * max_value(l.color.x, max_value(l.color.y, l.color.z));
  if (l.type == LightType::directional) return cutoff > 0.0 && brightest < cutoff ? 0.0 : 1e300;
  double reach = l.range > 0.0 ? l.range : 1e300;
  if (cutoff > 0.0) reach = min_value(reach, sqrt(max_value(brightest, 0.0) / cutoff));
  return reach;
}

// Whether light l (with reach `reach`, light_reach) may add to some point of the ball of radius
// r about c. Spot cones: the ball's distance to the cone's surface (or to its apex, where the
// nearest point of the cone is the apex) against r; cones of 90 degrees or more are not tested.
DV_HD inline bool light_may_reach_ball(const LightView& l, double reach, const dvec3& c, double r) {
  if (reach <= 0.0) return false;
  if (l.type == LightType::directional) return true;
  const dvec3 v = c - l.position;
  const double dist = glm::length(v);
  if (reach < 1e300 && dist - r > reach) return false;
  if (l.type != LightType::spot || !(l.cos_cutoff > 0.0)) return true;
  const double along = glm::dot(v, l.direction);
  const double across = sqrt(max_value(dist * dist - along * along, 0.0));
  const double cos_a = min_value(l.cos_cutoff, 1.0);
  const double sin_a = sqrt(max_value(1.0 - cos_a * cos_a, 0.0));
  const double to_cone =
      along * cos_a + across * sin_a >= 0.0 ? across * cos_a - along * sin_a : dist;
  return to_cone <= r;
}

// The masks of one frame's tiles (empty: every pixel evaluates every light).
struct LightTilesView {
  View<const uint32_t> masks;  // tile (ty * tiles_x + tx), then words of 32 lights each
  int tiles_x = 0;
  int words = 0;

  // The mask of pixel (x, y)'s tile, nullptr for every light.
  DV_HD const uint32_t* mask_of_pixel(int x, int y) const {
    if (masks.size == 0) return nullptr;
    const int64_t tile = int64_t(y / kLightTilePixels) * tiles_x + x / kLightTilePixels;
    return masks.data + tile * words;
  }
};

struct LightTiles {
  Buffer<uint32_t> masks;
  int tiles_x = 0;
  int tiles_y = 0;
  int words = 0;
  bool every_light = false;  // culling off: every mask lists every light
  LightTilesView view() const { return {masks.const_view(), tiles_x, words}; }
  // Whether culling made the masks (not none, nor culling off's lists of every light).
  bool culled() const { return masks.size() > 0 && !every_light; }
};

// Lights per pixel of a frame width x height: their sum over the pixels and their most (every
// pixel evaluates all `lights` when `tiles` holds no masks or lists every light). Reads the masks
// back to the host only when culling made them.
struct ListedLights {
  unsigned long long sum = 0;
  unsigned long long max = 0;
};
ListedLights count_listed_lights(const LightTiles& tiles, int width, int height, int lights);

// The tiles' masks of the scene's lights for `camera` (its width, height, near plane), in the
// backend's memory: every light in every tile when culling is off; empty with no light, or one
// light and cut-off 0 or culling off.
// Throws Error for a negative or non-finite cut-off.
LightTiles build_light_tiles(Backend backend, const SceneView& scene, const Camera& camera,
                             const LightCulling& culling);

}  // namespace dv
