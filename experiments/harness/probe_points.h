// Deterministic probe points for accuracy measurements: points on surfaces (an object chosen
// uniformly among those with visible surfaces, alpha > 0, then a triangle by area, then a
// uniform point on it, no offset; optionally on the isosurfaces of volumes) and points inside media
// (uniform in the world box of an object with an interior, kept when the point is inside some
// medium by the fragment walk's media_containing). The same seed gives the same points on every
// machine (own uniform from mt19937_64, no std distributions).
// The third class, `visible`, weights the error as the image does: the surface points
// the camera's pixels see (engine/raster/visible_surface.h: the pixel-centre ray's nearest
// surface with alpha > 0), pixels drawn uniformly without replacement among those that see one.
// Medium points along the camera rays are left out on purpose: a pixel's medium contribution is
// an integral along its ray weighted by the transmittance to the eye, which one point per pixel
// would not weight as the image does; the world-uniform `medium` class covers media.
#pragma once

#include <cstdint>
#include <vector>

#include "core/math.h"
#include "engine/raster/visible_surface.h"
#include "engine/scene/scene.h"
#include "engine/scene/scene_view.h"

namespace dv {

enum class ProbeClass : uint8_t { surface, medium, visible };
const char* to_string(ProbeClass c);

struct ProbePoints {
  std::vector<dvec3> points;
  std::vector<ProbeClass> classes;  // per point
};

// `count` points, round(count * medium_fraction) of them inside media when the scene has any
// (fewer when rejection sampling finds none within 200 tries per point); `host` is the scene in
// host memory. With `isosurface` >= 0 the volumes' isosurfaces at that density are surfaces too
// (Hadwiger 2006's isosurface self-shadowing): a surface probe picks uniformly among the visible
// meshes and the volumes, and on a volume takes the first crossing of the isovalue along a line
// from a uniform point of its box in a uniform direction.
ProbePoints make_probe_points(const Scene& scene, const SceneData& host, int count,
                              double medium_fraction, uint64_t seed, double isosurface = -1.0);

// `count` of the points `view` sees (every one when fewer pixels see a surface), in the order
// drawn, all of class `visible`; none when no pixel sees a surface. Compute `view` on the host
// (Backend::cpu) so the points are the same on every machine.
ProbePoints make_visible_probe_points(const VisibleSurface& view, int count, uint64_t seed);

}  // namespace dv
