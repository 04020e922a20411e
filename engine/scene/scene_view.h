// The scene as kernels see it: flat world-space arrays behind plain views, identical on CPU and
// CUDA. SceneData owns the arrays (host or device memory) and builds them from a Scene once;
// kernels receive SceneView by value.
#pragma once

#include <cstdint>

#include "core/math.h"
#include "cuda/buffer.h"
#include "engine/scene/bvh.h"
#include "engine/scene/scene.h"

namespace dv {

struct ObjectView {
  dvec3 color;
  double ambient, diffuse, specular, shininess;
  double alpha;         // surface opacity per crossing
  double transmission;  // glass part of the surface (surface_transmittance.h)
  double ior;           // the glass part's index of refraction (Fresnel)
  InteriorKind interior;
  double sigma;     // constant interior: the extinction the scalar storages carry
  dvec3 sigma_rgb;  // constant interior per channel (camera pass, oracle, colour side channel)
  int32_t volume;   // index into SceneView::volumes, or -1
  int32_t transfer_first, transfer_count;
  double step;           // volume ray-marching step (world units)
  dmat4 world_to_grid;   // world position -> continuous grid index (i, j, k)
  ivec3 bricks;          // volume: empty-space bricks per axis (kBrickCells cells each)
  int64_t brick_offset;  // volume: first flag in SceneView::brick_empty
  // Base-colour texture (Material::base_texture): index into SceneView::textures or -1; with
  // one, alpha and transmission above are those of full coverage (texture_sampling.h).
  int32_t texture;
  AlphaMode alpha_mode;
  double alpha_cutoff;
  double coverage_factor;
  glm::dmat3 uv_transform;
  dvec3 emission;  // Material::emission (camera pass only)
  // Material::emissive_texture (index into SceneView::textures or -1) and its UV transform.
  int32_t emissive_texture;
  glm::dmat3 emissive_uv_transform;
  // The base-colour texture has colour (texture_has_colour, engine/scene/scene.h): glass it
  // covers tints light even under a grey factor.
  bool texture_colour;
};

// A texture's place in SceneView::texels (RGBA8 rows from the top) and its sampler.
struct TextureView {
  int32_t width, height;
  int64_t offset;  // first byte
  TextureWrap wrap_s, wrap_t;
  TextureFilter filter;
};

// Cells per side of the bricks used for empty-space skipping (Hadwiger et al. 2006, §3).
inline constexpr int kBrickCells = 8;

struct VolumeView {
  ivec3 dims;
  int64_t offset;  // first density sample in SceneView::densities
};

struct LightView {
  LightType type;
  dvec3 position;
  dvec3 direction;    // unit; spot and directional
  double cos_cutoff;  // spot: cos(cutoff)
  double cos_inner;   // spot: cos(cutoff - penumbra)
  dvec3 color;
  double intensity;
  bool gltf_cone;  // spot: KHR_lights_punctual's squared linear falloff, not smoothstep
  double range;    // KHR_lights_punctual range window, 0: none
};

// Whether unit direction `from_light` (from a spot light's position toward a point) leaves the
// light's cone; the boundary is inside. Lights of other types have no cone.
DV_HD inline bool outside_spot_cone(const LightView& l, const dvec3& from_light) {
  return l.type == LightType::spot && glm::dot(from_light, l.direction) < l.cos_cutoff;
}

struct SceneView {
  View<const dvec3> vertices;     // world space
  View<const u32vec3> triangles;  // BVH order
  View<const uint32_t> triangle_object;
  View<const BvhNode> nodes;
  View<const ObjectView> objects;
  View<const VolumeView> volumes;
  View<const float> densities;
  View<const TransferPoint> transfer;
  View<const uint8_t> brick_empty;  // 1: extinction is zero everywhere in the brick
  View<const LightView> lights;
  // Per triangle corner (3 * BVH-order triangle + k), empty when no object needs them: texture
  // coordinates (objects with a texture) and unit world-space shading normals (zero: none).
  View<const dvec2> corner_uvs;
  View<const dvec3> corner_normals;
  View<const TextureView> textures;
  View<const uint8_t> texels;
  View<const double> srgb_to_linear;  // 256 entries when there are textures
  Aabb bounds;                        // world bounds of all triangles
  double diagonal;                    // length of the bounds' diagonal (scale for tolerances)
};

struct SceneDataOptions {
  bool empty_space_skipping = true;  // false: no brick is flagged empty (for comparisons)
};

class SceneData {
 public:
  SceneData(const Scene& scene, Memory memory, const SceneDataOptions& options = {});
  const SceneView& view() const { return view_; }
  Memory memory() const { return memory_; }
  int64_t triangle_count() const { return triangles_.size(); }
  int bvh_depth() const { return bvh_depth_; }
  // BVH position of each input triangle is not needed outside; input triangle of a BVH slot:
  const std::vector<uint32_t>& bvh_order() const { return order_; }
  // The lights in host memory whatever memory the view is in (host-side planning needs them).
  const std::vector<LightView>& host_lights() const { return host_lights_; }
  // World bounds of each object's triangles, in scene order (host-side planning: clusters).
  const std::vector<Aabb>& host_object_bounds() const { return host_object_bounds_; }
  // Each object's kernel record in host memory (the effect planner reads materials from it).
  const std::vector<ObjectView>& host_objects() const { return host_objects_; }
  // A content hash per object: its world-space triangles, material, interior, transfer function
  // and volume densities. Equal hashes: the object casts the same shadows (planner caches).
  const std::vector<uint64_t>& host_object_hashes() const { return host_object_hashes_; }

 private:
  Memory memory_;
  Buffer<dvec3> vertices_;
  Buffer<u32vec3> triangles_;
  Buffer<uint32_t> triangle_object_;
  Buffer<BvhNode> nodes_;
  Buffer<ObjectView> objects_;
  Buffer<VolumeView> volumes_;
  Buffer<float> densities_;
  Buffer<TransferPoint> transfer_;
  Buffer<uint8_t> brick_empty_;
  Buffer<LightView> lights_;
  Buffer<dvec2> corner_uvs_;
  Buffer<dvec3> corner_normals_;
  Buffer<TextureView> textures_;
  Buffer<uint8_t> texels_;
  Buffer<double> srgb_to_linear_;
  std::vector<uint32_t> order_;
  std::vector<LightView> host_lights_;
  std::vector<Aabb> host_object_bounds_;
  std::vector<ObjectView> host_objects_;
  std::vector<uint64_t> host_object_hashes_;
  int bvh_depth_ = 0;
  SceneView view_{};
};

// Converts a host light into its kernel form (normalised direction, cosines).
LightView make_light_view(const Light& light);

}  // namespace dv
