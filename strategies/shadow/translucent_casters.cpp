// gather_translucent_casters (see translucent_casters.h).
#include "strategies/shadow/translucent_casters.h"

#include <algorithm>
#include <vector>

#include "cuda/buffer.h"

namespace dv {

nlohmann::json TranslucentCasters::json() const {
  return {{"objects", objects},
          {"alpha_min", alpha_min},
          {"alpha_max", alpha_max},
          {"alpha_mean", alpha_mean},
          {"alphas_differ", alpha_max > alpha_min}};
}

TranslucentCasters gather_translucent_casters(const SceneData& scene) {
  const SceneView& s = scene.view();
  const Memory memory = scene.memory();
  const std::vector<dvec3> vertices = to_host_vector(s.vertices, memory);
  const std::vector<u32vec3> triangles = to_host_vector(s.triangles, memory);
  const std::vector<uint32_t> owner = to_host_vector(s.triangle_object, memory);
  const std::vector<ObjectView> objects = to_host_vector(s.objects, memory);
  auto translucent = [&](uint32_t o) {
    const ObjectView& v = objects[o];
    return v.alpha > 0.0 && v.alpha < 1.0 && v.transmission <= 0.0;  // glass: the glass layer
  };
  TranslucentCasters out;
  std::vector<bool> seen(objects.size(), false);
  for (size_t t = 0; t < triangles.size(); ++t) {
    const uint32_t o = owner[t];
    if (!translucent(o)) continue;
    out.soup.add(vertices[triangles[t].x], vertices[triangles[t].y], vertices[triangles[t].z]);
    seen[o] = true;
  }
  double sum = 0.0;
  for (size_t o = 0; o < objects.size(); ++o) {
    if (!seen[o]) continue;
    const double a = objects[o].alpha;
    out.alpha_min = out.objects ? std::min(out.alpha_min, a) : a;
    out.alpha_max = out.objects ? std::max(out.alpha_max, a) : a;
    sum += a;
    ++out.objects;
  }
  if (out.objects) out.alpha_mean = sum / out.objects;
  return out;
}

}  // namespace dv
