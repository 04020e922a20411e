// Flattening of a Scene into world-space arrays plus a BVH (see scene_view.h).
#include "engine/scene/scene_view.h"

#include <algorithm>
#include <cmath>

#include "core/content_hash.h"
#include "engine/scene/volume_sampling.h"

namespace dv {

LightView make_light_view(const Light& l) {
  LightView v{};
  v.type = l.type;
  v.position = l.position;
  v.direction = glm::length(l.direction) > 0 ? glm::normalize(l.direction) : dvec3(0, -1, 0);
  const double deg = 3.14159265358979323846 / 180.0;
  v.cos_cutoff = std::cos(l.cutoff_deg * deg);
  v.cos_inner = std::cos(std::max(0.0, l.cutoff_deg - l.penumbra_deg) * deg);
  v.color = l.color;
  v.intensity = l.intensity;
  v.gltf_cone = l.gltf_cone;
  v.range = l.range;
  return v;
}

namespace {

// Largest extinction of a piecewise-linear transfer function over densities [lo, hi]: at the
// interval's ends or at a control point inside it.
double max_sigma(const TransferFunction& tf, double lo, double hi) {
  auto sigma_at = [&](double d) {
    return evaluate_transfer(tf.points.data(), int(tf.points.size()), d).sigma;
  };
  double m = std::max(sigma_at(lo), sigma_at(hi));
  for (const TransferPoint& p : tf.points)
    if (p.density > lo && p.density < hi) m = std::max(m, p.sigma);
  return m;
}

// Flags the bricks of a volume whose extinction is zero everywhere: the range of the samples
// that trilinear interpolation inside the brick can reach maps to zero extinction.
void flag_empty_bricks(const VolumeGrid& g, const TransferFunction& tf, ObjectView& o,
                       std::vector<uint8_t>& flags) {
  for (int a = 0; a < 3; ++a)
    o.bricks[a] = std::max(1, (g.dims[a] - 1 + kBrickCells - 1) / kBrickCells);
  o.brick_offset = int64_t(flags.size());
  for (int bz = 0; bz < o.bricks.z; ++bz)
    for (int by = 0; by < o.bricks.y; ++by)
      for (int bx = 0; bx < o.bricks.x; ++bx) {
        float lo = 1e30f, hi = -1e30f;
        for (int z = bz * kBrickCells; z <= std::min((bz + 1) * kBrickCells, g.dims.z - 1); ++z)
          for (int y = by * kBrickCells; y <= std::min((by + 1) * kBrickCells, g.dims.y - 1); ++y)
            for (int x = bx * kBrickCells; x <= std::min((bx + 1) * kBrickCells, g.dims.x - 1);
                 ++x) {
              const float d = g.density[(size_t(z) * g.dims.y + y) * g.dims.x + x];
              lo = std::min(lo, d);
              hi = std::max(hi, d);
            }
        flags.push_back(max_sigma(tf, lo, hi) <= 0.0 ? 1 : 0);
      }
}

ObjectView make_object_view(const Scene& scene, const Object& obj,
                            std::vector<TransferPoint>& transfer,
                            std::vector<uint8_t>& brick_empty) {
  ObjectView o{};
  const Material& m = obj.material;
  o.color = m.color;
  o.ambient = m.ambient;
  o.diffuse = m.diffuse;
  o.specular = m.specular;
  o.shininess = m.shininess;
  o.alpha = m.alpha;
  o.transmission = m.transmission;
  o.ior = m.ior;
  o.interior = obj.interior.kind;
  const bool constant = obj.interior.kind == InteriorKind::constant;
  o.sigma = constant ? obj.interior.sigma : 0.0;
  o.sigma_rgb = constant ? obj.interior.sigma * obj.interior.sigma_tint : dvec3(0.0);
  o.volume = obj.interior.kind == InteriorKind::volume ? obj.interior.volume : -1;
  o.transfer_first = int32_t(transfer.size());
  o.transfer_count = int32_t(obj.interior.transfer.points.size());
  transfer.insert(transfer.end(), obj.interior.transfer.points.begin(),
                  obj.interior.transfer.points.end());
  o.texture = m.base_texture;
  o.alpha_mode = m.alpha_mode;
  o.alpha_cutoff = m.alpha_cutoff;
  o.coverage_factor = m.coverage_factor;
  o.uv_transform = m.uv_transform;
  o.emission = m.emission;
  o.emissive_texture = m.emissive_texture;
  o.emissive_uv_transform = m.emissive_uv_transform;
  o.texture_colour =
      m.base_texture >= 0 && texture_has_colour(scene.textures[size_t(m.base_texture)]);
  o.world_to_grid = dmat4(1.0);
  o.step = 0.0;
  if (o.volume >= 0) {
    const VolumeGrid& g = scene.volumes[o.volume];
    dmat4 object_to_grid(1.0);
    for (int a = 0; a < 3; ++a) {
      object_to_grid[a][a] = 1.0 / g.spacing[a];
      object_to_grid[3][a] = -g.origin[a] / g.spacing[a];
    }
    o.world_to_grid = object_to_grid * glm::inverse(obj.transform);
    // Default step: half the smallest cell edge, measured in world units.
    double cell = 1e300;
    for (int a = 0; a < 3; ++a) {
      dvec3 edge = dvec3(obj.transform * dvec4(g.spacing[a] * (a == 0), g.spacing[a] * (a == 1),
                                               g.spacing[a] * (a == 2), 0.0));
      cell = std::min(cell, glm::length(edge));
    }
    o.step = obj.interior.step > 0 ? obj.interior.step : 0.5 * cell;
    flag_empty_bricks(g, obj.interior.transfer, o, brick_empty);
  }
  return o;
}

// What an object contributes to images and shadows, hashed: its world-space mesh, its kernel
// record (without offsets into the shared arrays, which move when other objects change), its
// transfer function and its volume's densities.
uint64_t object_content_hash(const Scene& scene, const Object& obj, const ObjectView& o) {
  ContentHash h;
  const TriangleMesh& mesh = scene.meshes[obj.mesh];
  h.add(obj.transform).add(uint64_t(mesh.positions.size())).add(uint64_t(mesh.triangles.size()));
  for (const dvec3& p : mesh.positions) h.add(p);
  h.bytes(mesh.triangles.data(), mesh.triangles.size() * sizeof(u32vec3));
  h.add(o.color).add(o.ambient).add(o.diffuse).add(o.specular).add(o.shininess);
  h.add(o.alpha).add(o.transmission).add(o.interior).add(o.sigma).add(o.sigma_rgb).add(o.step);
  if (o.transmission > 0.0) h.add(o.ior);  // grey scenes keep their hashes
  h.add(o.world_to_grid);
  for (const TransferPoint& t : obj.interior.transfer.points)
    h.add(t.density).add(t.color).add(t.sigma);
  if (o.volume >= 0) {
    const VolumeGrid& g = scene.volumes[size_t(o.volume)];
    h.add(g.dims.x).add(g.dims.y).add(g.dims.z);
    h.bytes(g.density.data(), g.density.size() * sizeof(float));
  }
  if (o.texture >= 0) {
    const Texture& t = scene.textures[size_t(o.texture)];
    h.add(int(o.alpha_mode)).add(o.alpha_cutoff).add(o.coverage_factor).add(t.width).add(t.height);
    h.add(int(t.wrap_s)).add(int(t.wrap_t)).add(int(t.filter));
    h.bytes(t.rgba.data(), t.rgba.size());
    h.bytes(mesh.corner_uvs.data(), mesh.corner_uvs.size() * sizeof(dvec2));
    for (int c = 0; c < 3; ++c) h.add(dvec3(o.uv_transform[c]));
  }
  return h.value();
}

// The 256 sRGB-encoded byte values decoded to linear (IEC 61966-2-1), computed once on the
// host so that host and device decode texels from the same table.
std::vector<double> srgb_decode_table() {
  std::vector<double> table(256);
  for (int i = 0; i < 256; ++i) {
    const double c = i / 255.0;
    table[size_t(i)] = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  }
  return table;
}

// Unit world-space normal of object-space normal n under `transform` (zero stays zero).
dvec3 world_normal(const glm::dmat3& normal_matrix, const dvec3& n) {
  const dvec3 w = normal_matrix * n;
  const double len = glm::length(w);
  return len > 0.0 && std::isfinite(len) ? w / len : dvec3(0.0);
}

}  // namespace

SceneData::SceneData(const Scene& scene, Memory memory, const SceneDataOptions& options)
    : memory_(memory) {
  std::vector<dvec3> vertices;
  std::vector<u32vec3> tris;
  std::vector<uint32_t> tri_object;
  // Corner attributes only where some object needs them: untextured, unsmoothed scenes carry
  // no extra bytes.
  bool any_uvs = false, any_normals = false;
  for (const Object& obj : scene.objects) {
    any_uvs |= obj.material.base_texture >= 0 || obj.material.emissive_texture >= 0;
    any_normals |= !scene.meshes[obj.mesh].corner_normals.empty();
  }
  std::vector<dvec2> corner_uvs;
  std::vector<dvec3> corner_normals;
  for (size_t oi = 0; oi < scene.objects.size(); ++oi) {
    const Object& obj = scene.objects[oi];
    const TriangleMesh& mesh = scene.meshes[obj.mesh];
    // A mirroring transform flips winding; keep outward normals outward.
    const bool flip = glm::determinant(obj.transform) < 0.0;
    const bool textured = obj.material.base_texture >= 0 || obj.material.emissive_texture >= 0;
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(obj.transform)));
    for (size_t t = 0; t < mesh.triangles.size(); ++t)
      for (int k : {0, flip ? 2 : 1, flip ? 1 : 2}) {
        const size_t corner = 3 * t + size_t(k);
        if (any_uvs) corner_uvs.push_back(textured ? mesh.corner_uvs[corner] : dvec2(0.0));
        if (any_normals)
          corner_normals.push_back(mesh.corner_normals.empty()
                                       ? dvec3(0.0)
                                       : world_normal(normal_matrix, mesh.corner_normals[corner]));
      }
    uint32_t base = uint32_t(vertices.size());
    for (const dvec3& p : mesh.positions) vertices.push_back(dvec3(obj.transform * dvec4(p, 1.0)));
    Aabb& object_box = host_object_bounds_.emplace_back();
    for (size_t v = base; v < vertices.size(); ++v) object_box.extend(vertices[v]);
    for (const u32vec3& t : mesh.triangles) {
      tris.push_back(flip ? u32vec3(t.x + base, t.z + base, t.y + base) : t + u32vec3(base));
      tri_object.push_back(uint32_t(oi));
    }
  }
  std::vector<Aabb> boxes(tris.size());
  Aabb bounds;
  for (size_t i = 0; i < tris.size(); ++i) {
    for (int k = 0; k < 3; ++k) boxes[i].extend(vertices[tris[i][k]]);
    bounds.extend(boxes[i]);
  }
  BvhBuild bvh = build_bvh(boxes);
  bvh_depth_ = bvh.depth;
  order_ = bvh.order;
  std::vector<u32vec3> sorted_tris(tris.size());
  std::vector<uint32_t> sorted_object(tris.size());
  std::vector<dvec2> sorted_uvs(corner_uvs.size());
  std::vector<dvec3> sorted_normals(corner_normals.size());
  for (size_t i = 0; i < tris.size(); ++i) {
    sorted_tris[i] = tris[bvh.order[i]];
    sorted_object[i] = tri_object[bvh.order[i]];
    for (size_t k = 0; k < 3; ++k) {
      if (any_uvs) sorted_uvs[3 * i + k] = corner_uvs[3 * bvh.order[i] + k];
      if (any_normals) sorted_normals[3 * i + k] = corner_normals[3 * bvh.order[i] + k];
    }
  }
  std::vector<TextureView> textures;
  std::vector<uint8_t> texels;
  for (const Texture& t : scene.textures) {
    textures.push_back({t.width, t.height, int64_t(texels.size()), t.wrap_s, t.wrap_t, t.filter});
    texels.insert(texels.end(), t.rgba.begin(), t.rgba.end());
  }
  const std::vector<double> srgb = textures.empty() ? std::vector<double>() : srgb_decode_table();

  std::vector<TransferPoint> transfer;
  std::vector<uint8_t> brick_empty;
  std::vector<ObjectView> objects;
  for (const Object& obj : scene.objects)
    objects.push_back(make_object_view(scene, obj, transfer, brick_empty));
  if (!options.empty_space_skipping) std::fill(brick_empty.begin(), brick_empty.end(), uint8_t(0));
  std::vector<VolumeView> volumes;
  std::vector<float> densities;
  for (const VolumeGrid& g : scene.volumes) {
    volumes.push_back({g.dims, int64_t(densities.size())});
    densities.insert(densities.end(), g.density.begin(), g.density.end());
  }
  std::vector<LightView> lights;
  for (const Light& l : scene.lights) lights.push_back(make_light_view(l));
  host_objects_ = objects;
  for (size_t oi = 0; oi < scene.objects.size(); ++oi)
    host_object_hashes_.push_back(object_content_hash(scene, scene.objects[oi], objects[oi]));

  vertices_ = Buffer<dvec3>(memory, vertices, "scene vertices");
  triangles_ = Buffer<u32vec3>(memory, sorted_tris, "scene triangles");
  triangle_object_ = Buffer<uint32_t>(memory, sorted_object, "triangle objects");
  nodes_ = Buffer<BvhNode>(memory, bvh.nodes, "bvh nodes");
  objects_ = Buffer<ObjectView>(memory, objects, "objects");
  volumes_ = Buffer<VolumeView>(memory, volumes, "volumes");
  densities_ = Buffer<float>(memory, densities, "volume densities");
  transfer_ = Buffer<TransferPoint>(memory, transfer, "transfer functions");
  brick_empty_ = Buffer<uint8_t>(memory, brick_empty, "empty bricks");
  lights_ = Buffer<LightView>(memory, lights, "lights");
  corner_uvs_ = Buffer<dvec2>(memory, sorted_uvs, "texture coordinates");
  corner_normals_ = Buffer<dvec3>(memory, sorted_normals, "vertex normals");
  textures_ = Buffer<TextureView>(memory, textures, "textures");
  texels_ = Buffer<uint8_t>(memory, texels, "texture texels");
  srgb_to_linear_ = Buffer<double>(memory, srgb, "sRGB decoding table");
  host_lights_ = lights;

  view_.vertices = vertices_.const_view();
  view_.triangles = triangles_.const_view();
  view_.triangle_object = triangle_object_.const_view();
  view_.nodes = nodes_.const_view();
  view_.objects = objects_.const_view();
  view_.volumes = volumes_.const_view();
  view_.densities = densities_.const_view();
  view_.transfer = transfer_.const_view();
  view_.brick_empty = brick_empty_.const_view();
  view_.lights = lights_.const_view();
  view_.corner_uvs = corner_uvs_.const_view();
  view_.corner_normals = corner_normals_.const_view();
  view_.textures = textures_.const_view();
  view_.texels = texels_.const_view();
  view_.srgb_to_linear = srgb_to_linear_.const_view();
  view_.bounds = bounds;
  view_.diagonal = bounds.empty() ? 0.0 : glm::length(bounds.extent());
}

}  // namespace dv
