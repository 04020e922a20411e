// How scenes that bring no lights are staged, like a model viewer would: a three-quarter view
// of the bounds when there is no camera either, a ground plane under the model, a key spot
// light from above and beside the camera whose cone (and so its shadow map) is fitted to the
// casters and their shadow on the ground, and a dim fill along the camera's view.
#pragma once

#include <optional>
#include <vector>

#include "engine/scene/scene.h"

namespace dv {

// Azimuth (degrees from +z towards +x about +y) and elevation of the default view direction.
inline constexpr double kDefaultViewAzimuthDeg = 35.0;
inline constexpr double kDefaultViewElevationDeg = 25.0;
// Where the key light stands: this many degrees round from the camera's azimuth (to its
// left), this high, at this many bounding-sphere radii from the model's centre.
inline constexpr double kKeyAzimuthFromCameraDeg = -60.0;
inline constexpr double kKeyElevationDeg = 55.0;
inline constexpr double kKeyDistanceRadii = 4.0;

// A 640x480 camera with a 45 degree field of view looking at the centre of `bounds` from the
// three-quarter direction above, far enough that the bounding sphere fits the vertical (the
// smaller) field of view.
Camera default_camera(const Aabb& bounds);

// The key spot light and the fill for casters within `casters`, seen from `camera`:
//   - key: kKeyAzimuthFromCameraDeg round from the camera's azimuth about the casters' centre
//     (the default view's azimuth when the camera looks straight down), kKeyElevationDeg up,
//     kKeyDistanceRadii bounding-sphere radii away, aimed at the centre with irradiance 1
//     there. Its cone is fitted to the casters: its full-intensity core holds every corner of
//     `casters` and, with a ground at height `ground_y`, the corners' shadows on it (with a
//     margin of lit ground around them); a narrow penumbra outside. A spot's shadow map covers
//     its cone, so the map spends its texels on the model rather than on empty ground.
//   - fill: a directional light of irradiance 0.25 shining along the camera's view direction.
std::vector<Light> default_lights(const Aabb& casters, const Camera& camera,
                                  std::optional<double> ground_y = std::nullopt);

// How far below the model's bounds the staged ground lies, in bounding-sphere radii. Not zero,
// so that the model's bottom faces never tie with the ground in the camera's depth order; and
// wider than the receiver bias of the staged key light's maps on the ground at their default
// resolution 1024 (engine/raster/light_faces.h, receiver_depth), so that a translucent bottom
// face or a BLEND layer resting on the ground still shadows it under the key as it does in the
// exact oracle: the gap is about 2.7x dsm's bias there, 1.5x with its bilinear filter, 1.9x
// shadowmap's (tests/strategies/shadow/test_contact_shadows.cpp prints the margins). The fill
// light's orthographic map spans the whole ground and grazes it: its bias is larger than the gap.
inline constexpr double kGroundGapRadii = 0.01;

// Adds an opaque grey square object named "ground" kGroundGapRadii below the plane
// y = bounds.lo.y, centred under the bounds, 6 bounding-sphere radii wide, and returns its
// height. No-op (nullopt) when an object named "ground" exists.
std::optional<double> add_ground_plane(Scene& scene);

// Which scenes get a ground plane: staged: those whose lights are staged (the default); on:
// every scene (render --ground); off: none (render --no-ground).
enum class GroundPlane { staged, on, off };

struct StagingOptions {
  GroundPlane ground = GroundPlane::staged;
  // false: no lights are staged either (a command that reads only the geometry, as voxelize).
  bool lights = true;
};

// Stages a loaded scene (its camera set): a scene without lights gets a ground plane (unless
// ground is off) and then default_lights from its camera, fitted to its bounds and that ground;
// a scene with lights gets only a ground, and only when ground is on; options.lights false
// stages no lights (and no ground unless it is on). Returns whether the lights were staged.
bool stage_scene(Scene& scene, const StagingOptions& options);

}  // namespace dv
