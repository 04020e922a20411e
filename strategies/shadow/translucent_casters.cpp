// gather_translucent_casters (see translucent_casters.h).
#include "strategies/shadow/translucent_casters.h"

#include <algorithm>
#include <cmath>
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

std::vector<double> medium_crossing_alphas(const SceneData& scene) {
  const SceneView& s = scene.view();
  const std::vector<ObjectView>& objects = scene.host_objects();
  const std::vector<TransferPoint> transfer = to_host_vector(s.transfer, scene.memory());
  std::vector<double> alphas(objects.size(), 0.0);
  for (size_t i = 0; i < objects.size(); ++i) {
    const ObjectView& o = objects[i];
    double sigma = o.interior == InteriorKind::constant ? o.sigma : 0.0;
    if (o.interior == InteriorKind::volume)
      for (int32_t k = 0; k < o.transfer_count; ++k)
        sigma = std::max(sigma, transfer[size_t(o.transfer_first + k)].sigma);
    const dvec3 extent = scene.host_object_bounds()[i].extent();
    const double thickness = std::min(extent.x, std::min(extent.y, extent.z));
    if (sigma > 0.0 && thickness > 0.0) alphas[i] = 1.0 - std::exp(-0.5 * sigma * thickness);
  }
  return alphas;
}

std::vector<double> caster_alphas(const SceneData& scene) {
  const std::vector<ObjectView>& objects = scene.host_objects();
  std::vector<double> alphas = medium_crossing_alphas(scene);
  for (size_t i = 0; i < objects.size(); ++i) {
    const ObjectView& o = objects[i];
    const bool blend_texture = o.texture >= 0 && o.alpha_mode == AlphaMode::blend;
    alphas[i] = std::max(alphas[i], blend_texture ? o.alpha * o.coverage_factor : o.alpha);
  }
  return alphas;
}

TranslucentCasters gather_translucent_casters(const SceneData& scene) {
  const SceneView& s = scene.view();
  const Memory memory = scene.memory();
  const std::vector<dvec3> vertices = to_host_vector(s.vertices, memory);
  const std::vector<u32vec3> triangles = to_host_vector(s.triangles, memory);
  const std::vector<uint32_t> owner = to_host_vector(s.triangle_object, memory);
  const std::vector<ObjectView>& objects = scene.host_objects();
  const std::vector<double> surfaces = caster_alphas(scene);
  const std::vector<double> media = medium_crossing_alphas(scene);
  // Glass surfaces go into the opaque map's glass layer; a medium inside glass casts by its
  // boundary here.
  std::vector<double> alphas(objects.size());
  for (size_t o = 0; o < objects.size(); ++o)
    alphas[o] = objects[o].transmission > 0.0 ? media[o] : surfaces[o];
  auto translucent = [&](uint32_t o) { return alphas[o] > 0.0 && alphas[o] < 1.0; };
  TranslucentCasters out;
  std::vector<bool> seen(alphas.size(), false);
  for (size_t t = 0; t < triangles.size(); ++t) {
    const uint32_t o = owner[t];
    if (!translucent(o)) continue;
    out.soup.add(vertices[triangles[t].x], vertices[triangles[t].y], vertices[triangles[t].z]);
    seen[o] = true;
  }
  double sum = 0.0;
  for (size_t o = 0; o < alphas.size(); ++o) {
    if (!seen[o]) continue;
    const double a = alphas[o];
    out.alpha_min = out.objects ? std::min(out.alpha_min, a) : a;
    out.alpha_max = out.objects ? std::max(out.alpha_max, a) : a;
    sum += a;
    ++out.objects;
  }
  if (out.objects) out.alpha_mean = sum / out.objects;
  return out;
}

}  // namespace dv
