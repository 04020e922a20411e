// How scenes that bring no camera or lights are staged, like a model viewer would: a
// three-quarter view of the bounds, a key spot light from above and beside the camera that
// casts visible shadows, a dim fill from the camera's side, and an optional ground plane.
#pragma once

#include <vector>

#include "engine/scene/scene.h"

namespace dv {

// Azimuth (degrees from +z towards +x about +y) and elevation of the default view direction.
inline constexpr double kDefaultViewAzimuthDeg = 35.0;
inline constexpr double kDefaultViewElevationDeg = 25.0;

// A 640x480 camera with a 45 degree field of view looking at the centre of `bounds` from the
// three-quarter direction above, far enough that the bounding sphere fits the vertical (the
// smaller) field of view.
Camera default_camera(const Aabb& bounds);

// The key spot light (irradiance 1 at the bounds' centre, 60 degrees to the left of the view
// and 55 degrees up, its cone covering the ground plane's lit area) and a fill directional
// light of irradiance 0.25 shining along the view direction.
std::vector<Light> default_lights(const Aabb& bounds);

// Adds an opaque grey square object named "ground" just below the plane y = bounds.lo.y, centred
// under the bounds, 6 bounding-sphere radii wide. No-op when an object named "ground" exists.
void add_ground_plane(Scene& scene);

}  // namespace dv
