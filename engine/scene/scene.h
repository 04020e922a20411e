// The scene model: closed or open triangle meshes with a transform and a material, interiors
// (none, constant extinction, or a density volume under a transfer function), lights and a
// camera. Host-side owning types; engine/scene/scene_view.h flattens them for kernels.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace dv {

// Triangle mesh in object space. Indices are 0-based into positions. Texture coordinates and
// shading normals, where the source has them, belong to triangle corners (three per triangle,
// in the triangle's vertex order), not to positions: positions stay shared across UV and
// normal seams, so a textured closed mesh is still closed. Each is empty or 3 * triangles long.
struct TriangleMesh {
  std::string name;  // generator name or file path, for messages
  std::vector<dvec3> positions;
  std::vector<u32vec3> triangles;
  std::vector<dvec2> corner_uvs;
  std::vector<dvec3> corner_normals;  // object space, not necessarily unit
};

enum class TextureWrap : uint8_t { repeat, clamp, mirror };
enum class TextureFilter : uint8_t { nearest, bilinear };

// A decoded image with its sampler: 8-bit RGBA, rows from the top (glTF's UV origin), RGB in
// sRGB encoding (decoded to linear when sampled), alpha linear.
struct Texture {
  std::string name;  // for messages
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4
  TextureWrap wrap_s = TextureWrap::repeat;
  TextureWrap wrap_t = TextureWrap::repeat;
  TextureFilter filter = TextureFilter::bilinear;
};

// How a base-colour texture's alpha covers the surface (glTF alphaMode): coverage = factor *
// texel alpha, then opaque: 1; mask: 1 at or above the cutoff, else 0; blend: as is.
enum class AlphaMode : uint8_t { opaque, mask, blend };

// Surface material: Phong parameters plus surface opacity. `alpha` is the opaque part of the
// surface, `transmission` (at most 1 - alpha) its glass part: light through one crossing is
// multiplied by (1 - alpha - transmission) + transmission (1 - F) color per channel, F the
// Fresnel reflectance for `ior` (engine/scene/surface_transmittance.h; `color` drops out when
// the object has an interior). Without transmission that is 1 - alpha; the camera pass and
// every shadow method follow the same rule. A base-colour texture scales `alpha` and
// `transmission` by the coverage at the hit and `color` by the texel.
struct Material {
  dvec3 color{0.8, 0.8, 0.8};
  double ambient = 0.1;
  double diffuse = 0.8;
  double specular = 0.2;
  double shininess = 32.0;
  double alpha = 1.0;
  double transmission = 0.0;
  double ior = 1.5;  // index of refraction of the glass part (KHR_materials_ior)
  // A base-colour texture (index into Scene::textures, -1: none). With one, colour is
  // multiplied by the texel's linear RGB, and alpha and transmission are those of a fully
  // covered point, scaled by the coverage there (alpha_mode of coverage_factor * texel alpha);
  // uv_transform maps the mesh's corner UVs to texture UVs (KHR_texture_transform).
  int base_texture = -1;
  AlphaMode alpha_mode = AlphaMode::opaque;
  double alpha_cutoff = 0.5;
  double coverage_factor = 1.0;
  glm::dmat3 uv_transform{1.0};
  // Light the surface emits towards the camera (glTF emissiveFactor times emissiveStrength),
  // added in the camera pass where the surface covers (alpha + transmission); it lights nothing
  // else and casts no shadow. An emissive texture (index into Scene::textures, -1: none)
  // multiplies it by the texel's linear RGB, read through the mesh's texture coordinates and
  // its own emissive_uv_transform.
  dvec3 emission{0.0};
  int emissive_texture = -1;
  glm::dmat3 emissive_uv_transform{1.0};
};

// One control point of a piecewise-linear transfer function: density -> colour and extinction
// (per world unit). Outside the first/last point the end values hold.
struct TransferPoint {
  double density = 0.0;
  dvec3 color{1.0, 1.0, 1.0};
  double sigma = 0.0;
};

struct TransferFunction {
  std::vector<TransferPoint> points;  // sorted by density, at least one
};

// Densities on a vertex-centred grid: sample (i,j,k) sits at origin + (i,j,k) * spacing in the
// object's space; lookups outside the grid clamp to the edge samples.
struct VolumeGrid {
  std::string name;
  ivec3 dims{0, 0, 0};
  dvec3 origin{0.0};
  dvec3 spacing{1.0};
  std::vector<float> density;  // x fastest, then y, then z

  int64_t voxel_count() const { return int64_t(dims.x) * dims.y * dims.z; }
  Aabb bounds() const { return {origin, origin + dvec3(dims - 1) * spacing}; }
};

enum class InteriorKind : uint8_t { none, constant, volume };

struct Interior {
  InteriorKind kind = InteriorKind::none;
  double sigma = 0.0;  // constant: extinction per world unit (absorption only), for shadows
  // constant: the extinction of channel c is sigma * sigma_tint[c] (tinted media, mean 1), in
  // the camera pass and in shadows (the storages carry sigma, a colour side channel the rest).
  // Grey media keep [1, 1, 1].
  dvec3 sigma_tint{1.0};
  int volume = -1;  // volume: index into Scene::volumes
  TransferFunction transfer;
  double step = 0.0;  // volume: ray-marching step of the renderer in world units (0: half a cell)
};

struct Object {
  std::string name;
  int mesh = -1;  // index into Scene::meshes
  dmat4 transform{1.0};
  Material material;
  Interior interior;
};

enum class LightType : uint8_t { spot, omni, directional };

struct Light {
  LightType type = LightType::spot;
  dvec3 position{0.0};
  dvec3 direction{0.0, -1.0, 0.0};  // spot and directional: where the light shines
  double cutoff_deg = 30.0;         // spot: half-angle of the cone
  double penumbra_deg = 0.0;        // spot: width of the fade inside the cone edge
  dvec3 color{1.0, 1.0, 1.0};
  // spot/omni: radiant intensity I (falls off with 1/d^2): a white surface of diffuse 1
  // facing the light at distance d shows I / d^2 before exposure; directional: irradiance.
  double intensity = 1.0;
  // glTF lights (KHR_lights_punctual): the spec's cone falloff (squared, linear in the cosine)
  // instead of the smoothstep penumbra, and the range window (0: no range).
  bool gltf_cone = false;
  double range = 0.0;
  // Where the intensity came from, for `info`: the unit ("cd", "lx") and value before the
  // conversion, or an empty unit for deepvox's own scale.
  std::string source_unit;
  double source_intensity = 0.0;
};

struct Camera {
  dvec3 position{0.0, 1.0, 5.0};
  dvec3 target{0.0};
  dvec3 up{0.0, 1.0, 0.0};
  double fov_deg = 45.0;  // vertical
  int width = 640;
  int height = 480;
  double near_plane = 0.01;
};

struct Scene {
  std::string source;  // file the scene came from, for messages
  std::vector<TriangleMesh> meshes;
  std::vector<VolumeGrid> volumes;
  std::vector<Texture> textures;
  std::vector<Object> objects;
  std::vector<Light> lights;
  Camera camera;
  dvec3 background{0.0, 0.0, 0.0};
};

const char* to_string(LightType type);
const char* to_string(InteriorKind kind);

// World-space bounds of all objects (vertices after transforms).
Aabb world_bounds(const Scene& scene);

// How far apart (in sRGB bytes) a texel's R, G and B may be and the texel still count as grey.
inline constexpr int kGreyTexelTolerance = 2;

// Whether some texel of `texture` has colour: two of its RGB bytes differ by more than
// kGreyTexelTolerance. A base-colour texture with colour tints what crosses glass it covers, so
// the shadow methods must carry colour for it, not only for a coloured factor.
bool texture_has_colour(const Texture& texture);

// Whether crossings of `object` can tint light (the host form of tints_light,
// engine/scene/surface_transmittance.h): thin-walled glass whose base colour (factor, or the
// texels of its base-colour texture) is not grey, or a tinted constant medium.
bool object_tints_light(const Scene& scene, const Object& object);

// Checks invariants the renderer and oracle rely on (indices in range, finite numbers, closed
// meshes for interiors, sorted transfer functions); throws InputError naming scene.source.
// Closed meshes of objects with an interior are oriented outward (the oracle relies on it).
void validate_scene(Scene& scene);

}  // namespace dv
