// Deterministic probe points for accuracy measurements: points on surfaces (an object chosen
// uniformly among those with visible surfaces, alpha > 0, then a triangle by area, then a
// uniform point on it, no offset; optionally on the isosurfaces of volumes) and points inside media
// (uniform in the world box of an object with an interior, kept when the point is inside some
// medium by the fragment walk's media_containing). The same seed gives the same points on every
// machine (own uniform from mt19937_64, no std distributions).
#pragma once

#include <cstdint>
#include <vector>

#include "core/math.h"
#include "engine/scene/scene.h"
#include "engine/scene/scene_view.h"

namespace dv {

enum class ProbeClass : uint8_t { surface, medium };
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

}  // namespace dv
