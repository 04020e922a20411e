// Scene-model helpers: names, world bounds and the validation every loader ends with.
#include "engine/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.h"
#include "engine/scene/mesh_topology.h"

namespace dv {

const char* to_string(LightType type) {
  switch (type) {
    case LightType::spot:
      return "spot";
    case LightType::omni:
      return "omni";
    case LightType::directional:
      return "directional";
  }
  return "?";
}

const char* to_string(InteriorKind kind) {
  switch (kind) {
    case InteriorKind::none:
      return "none";
    case InteriorKind::constant:
      return "constant";
    case InteriorKind::volume:
      return "volume";
  }
  return "?";
}

bool texture_has_colour(const Texture& texture) {
  const std::vector<uint8_t>& rgba = texture.rgba;
  for (size_t i = 0; i + 2 < rgba.size(); i += 4) {
    const int r = rgba[i], g = rgba[i + 1], b = rgba[i + 2];
    if (std::max({r, g, b}) - std::min({r, g, b}) > kGreyTexelTolerance) return true;
  }
  return false;
}

namespace {

bool grey(const dvec3& c) {
  return c.x == c.y && c.y == c.z;
}

}  // namespace

bool object_tints_light(const Scene& scene, const Object& object) {
  const Material& m = object.material;
  const bool textured_colour =
      m.base_texture >= 0 && texture_has_colour(scene.textures[size_t(m.base_texture)]);
  const bool glass = m.transmission > 0.0 && object.interior.kind == InteriorKind::none &&
                     (!grey(m.color) || textured_colour);
  const bool medium = object.interior.kind == InteriorKind::constant &&
                      object.interior.sigma > 0.0 && !grey(object.interior.sigma_tint);
  return glass || medium;
}

Aabb world_bounds(const Scene& scene) {
  Aabb box;
  for (const Object& obj : scene.objects) {
    for (const dvec3& p : scene.meshes[obj.mesh].positions) {
      box.extend(dvec3(obj.transform * dvec4(p, 1.0)));
    }
  }
  return box;
}

namespace {

bool finite(const dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void validate_mesh(const std::string& where, const TriangleMesh& mesh) {
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    if (!finite(mesh.positions[i]))
      throw InputError(where, "vertex " + std::to_string(i) + " is not finite (NaN or Inf)");
  }
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      if (mesh.triangles[t][k] >= mesh.positions.size())
        throw InputError(where, "triangle " + std::to_string(t) + " uses vertex index " +
                                    std::to_string(mesh.triangles[t][k]) + " but the mesh has " +
                                    std::to_string(mesh.positions.size()) + " vertices");
    }
  }
  if (mesh.triangles.empty()) throw InputError(where, "mesh has no triangles");
  const size_t corners = 3 * mesh.triangles.size();
  if (!mesh.corner_uvs.empty() && mesh.corner_uvs.size() != corners)
    throw InputError(where, std::to_string(mesh.corner_uvs.size()) +
                                " texture coordinates, but its triangles have " +
                                std::to_string(corners) + " corners");
  if (!mesh.corner_normals.empty() && mesh.corner_normals.size() != corners)
    throw InputError(where, std::to_string(mesh.corner_normals.size()) +
                                " normals, but its triangles have " + std::to_string(corners) +
                                " corners");
}

void validate_texture(const std::string& where, const Texture& t) {
  if (t.width < 1 || t.height < 1) throw InputError(where, "texture has zero size");
  if (t.rgba.size() != size_t(t.width) * size_t(t.height) * 4)
    throw InputError(where, "texel count does not match the dimensions");
}

void validate_transfer(const std::string& where, const TransferFunction& tf) {
  if (tf.points.empty()) throw InputError(where, "transfer function has no points");
  for (size_t i = 0; i < tf.points.size(); ++i) {
    const TransferPoint& p = tf.points[i];
    if (!std::isfinite(p.density) || !finite(p.color) || !std::isfinite(p.sigma) || p.sigma < 0)
      throw InputError(
          where, "transfer point " + std::to_string(i) + " must have finite values and sigma >= 0");
    if (i > 0 && p.density < tf.points[i - 1].density)
      throw InputError(where, "transfer points must be sorted by density");
  }
}

}  // namespace

void validate_scene(Scene& scene) {
  const std::string& src = scene.source;
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    validate_mesh(src + ": mesh '" + scene.meshes[m].name + "'", scene.meshes[m]);
  for (const VolumeGrid& v : scene.volumes) {
    std::string where = src + ": volume '" + v.name + "'";
    if (v.dims.x < 1 || v.dims.y < 1 || v.dims.z < 1)
      throw InputError(where, "volume has zero size");
    if (int64_t(v.density.size()) != v.voxel_count())
      throw InputError(where, "density count does not match the dimensions");
    if (!(v.spacing.x > 0 && v.spacing.y > 0 && v.spacing.z > 0) || !finite(v.origin))
      throw InputError(where, "spacing must be positive and the origin finite");
  }
  for (const Texture& t : scene.textures) validate_texture(src + ": texture '" + t.name + "'", t);
  for (Object& obj : scene.objects) {
    std::string where = src + ": object '" + obj.name + "'";
    if (obj.mesh < 0 || obj.mesh >= int(scene.meshes.size()))
      throw InputError(where, "mesh index out of range");
    const Material& m = obj.material;
    for (const auto& [texture, what] :
         {std::pair{m.base_texture, "base-colour"}, std::pair{m.emissive_texture, "emissive"}}) {
      if (texture >= int(scene.textures.size()))
        throw InputError(where, std::string(what) + " texture index out of range");
      if (texture >= 0 && scene.meshes[obj.mesh].corner_uvs.empty())
        throw InputError(where, std::string("the material has a ") + what +
                                    " texture but the mesh has no texture coordinates");
    }
    if (!(m.coverage_factor >= 0.0 && m.coverage_factor <= 1.0))
      throw InputError(where, "material coverage factor must lie in [0, 1]");
    if (!finite(m.emission) || m.emission.x < 0.0 || m.emission.y < 0.0 || m.emission.z < 0.0)
      throw InputError(where, "material emission must be finite and >= 0");
    if (!(m.alpha >= 0.0 && m.alpha <= 1.0))
      throw InputError(where, "material alpha must lie in [0,1]");
    if (!finite(m.color)) throw InputError(where, "material colour is not finite");
    if (!(m.transmission >= 0.0 && m.transmission <= 1.0 - m.alpha + 1e-12))
      throw InputError(where, "material transmission must lie in [0, 1 - alpha]");
    if (!(m.ior >= 1.0 && std::isfinite(m.ior)))
      throw InputError(where, "material ior must be a finite number >= 1");
    if (std::abs(glm::determinant(obj.transform)) < 1e-300 ||
        !std::isfinite(glm::determinant(obj.transform)))
      throw InputError(where, "transform is singular or not finite");
    Interior& in = obj.interior;
    if (in.kind == InteriorKind::none) continue;
    if (in.kind == InteriorKind::constant && !(in.sigma >= 0.0 && std::isfinite(in.sigma)))
      throw InputError(where, "interior sigma must be finite and >= 0");
    if (in.kind == InteriorKind::constant && !(finite(in.sigma_tint) && in.sigma_tint.x >= 0.0 &&
                                               in.sigma_tint.y >= 0.0 && in.sigma_tint.z >= 0.0))
      throw InputError(where, "interior sigma must be >= 0 in every channel");
    if (in.kind == InteriorKind::volume) {
      if (in.volume < 0 || in.volume >= int(scene.volumes.size()))
        throw InputError(where, "interior volume index out of range");
      validate_transfer(where, in.transfer);
      if (!(in.step >= 0.0)) throw InputError(where, "interior step must be >= 0");
    }
    TriangleMesh& mesh = scene.meshes[obj.mesh];
    std::vector<OpenEdge> open = open_edges(mesh);
    if (!open.empty()) {
      std::string list;
      for (size_t i = 0; i < open.size() && i < 5; ++i)
        list += (i ? ", " : "") + std::to_string(open[i].a) + "-" + std::to_string(open[i].b);
      throw InputError(src + ": mesh '" + mesh.name + "'",
                       "object '" + obj.name + "' has an interior but its mesh is not closed: " +
                           std::to_string(open.size()) + " open edge(s) (vertex pairs " + list +
                           (open.size() > 5 ? ", ..." : "") + ")");
    }
    orient_outward(mesh);
  }
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    std::string where = src + ": light " + std::to_string(i);
    if (!finite(l.position) || !finite(l.direction) || !finite(l.color) ||
        !std::isfinite(l.intensity))
      throw InputError(where, "light values must be finite");
    if (l.type != LightType::omni && glm::length(l.direction) < 1e-12)
      throw InputError(where, "light direction must not be zero");
    if (l.type == LightType::spot && !(l.cutoff_deg > 0.0 && l.cutoff_deg <= 90.0))
      throw InputError(where, "spot cutoff must lie in (0, 90] degrees");
  }
  const Camera& c = scene.camera;
  if (c.width < 1 || c.height < 1 || c.width > 16384 || c.height > 16384)
    throw InputError(src + ": camera", "image size must be between 1 and 16384 pixels");
  if (!(c.fov_deg > 0.0 && c.fov_deg < 180.0))
    throw InputError(src + ": camera", "fov must lie in (0, 180) degrees");
  if (glm::length(c.target - c.position) < 1e-12)
    throw InputError(src + ": camera", "position equals target");
}

}  // namespace dv
