// glTF 2.0 import (.gltf with embedded or external buffers, and .glb) into deepvox's scene
// model, so scenes made in Blender & co. can be rendered and shadowed. tinygltf parses the file
// (compiled in render/load/gltf_impl.cpp); this importer validates everything it reads and maps it
// as documented below. The README points here for the mapping.
//
// How glTF maps onto dv::Scene
// ----------------------------
// Files and errors
//   - The file is read whole; bytes starting with "glTF" are parsed as GLB, anything else as
//     JSON. Missing or empty files, malformed JSON, a truncated or corrupt .glb, a bad buffer
//     URI: dv::InputError naming the file. tinygltf's own warnings become dv::log_warning.
//   - extensionsRequired may only name KHR_lights_punctual, KHR_materials_transmission,
//     KHR_materials_volume, KHR_materials_ior, KHR_materials_emissive_strength and
//     KHR_texture_transform. Any other
//     (KHR_mesh_quantization, KHR_draco_mesh_compression, ...) is an InputError naming it.
//     Unknown names in extensionsUsed only warn.
// Nodes and meshes
//   - The default scene (else scene 0) is walked; node transforms (matrix, or T * R * S) are
//     composed into world matrices. The hierarchy must be a tree (a node reached twice is an
//     InputError). Skins, morph targets and animations are ignored.
//   - Each primitive of mode TRIANGLES (4, the default), TRIANGLE_STRIP (5) or TRIANGLE_FAN
//     (6) becomes one dv::Object with its own TriangleMesh: positions (object space) from the
//     POSITION accessor, triangles from the indices accessor or 0..n-1; strips and fans are
//     converted to triangles and triangles that repeat a vertex index are dropped. The node's
//     world matrix goes into Object::transform. Vertices at identical positions are merged
//     (glTF splits them at normal seams) so closed shapes are closed by index; NORMAL and the
//     base-colour texture's TEXCOORD_n (FLOAT, or normalized UNSIGNED_BYTE/SHORT VEC2) are kept
//     per triangle corner (TriangleMesh::corner_normals, corner_uvs), so seams survive the
//     merge. Normals are interpolated for shading (not for shadows). A primitive
//     used by several nodes shares one TriangleMesh. POINTS and LINES primitives (modes 0-3)
//     and primitives without triangles are skipped with a warning.
//   - Every accessor is validated before it is read: indices of accessor, buffer view and
//     buffer in range; POSITION must be FLOAT VEC3, indices UNSIGNED_BYTE/SHORT/INT SCALAR;
//     byteOffset + stride * (count - 1) + element size must fit in the buffer view, and the
//     view in its buffer; sparse accessors and accessors without a buffer view are refused;
//     index values must be below the vertex count; positions must be finite. Each violation
//     is an InputError naming the file, the accessor and the mesh.
// Camera
//   - The first node in the walk with a perspective camera: position and orientation from its
//     world matrix (looks along local -Z, up is local +Y; target = position + view direction
//     times the distance to the centre of the scene bounds), fov_deg = yfov in degrees,
//     width = 640, height = round(640 / aspectRatio) (480 without aspectRatio), near_plane =
//     znear. Orthographic cameras are skipped with a warning.
//   - No camera: dv::default_camera (engine/scene/default_staging.h): fov 45 degrees, a
//   three-quarter
//     view of the world bounds' centre (35 degrees round from +Z towards +X, 25 degrees up),
//     far enough that the bounding sphere fits the vertical field of view.
// Lights (KHR_lights_punctual, attached to nodes)
//   - Position = node origin; a light shines along its node's local -Z. spot -> spot with
//     cutoff_deg = outerConeAngle (default pi/4) and penumbra_deg = outer - inner cone angle,
//     both in degrees, and the spec's cone falloff (Light::gltf_cone: (clamp((cos a - cos
//     outer) / max(cos inner - cos outer, 0.001), 0, 1))^2, a the angle to the axis); point
//     -> omni; directional -> directional. color is copied.
//   - Units: glTF intensity is photometric (candela = lm/sr for point and spot, lux = lm/m^2
//     for directional). deepvox's scale is radiometric: a light of intensity I gives
//     irradiance I / d^2 (W/m^2) at distance d, and a white surface of diffuse 1 facing it
//     shows I / d^2 before exposure (render --exposure, --tonemap). The conversion is the
//     spec's luminous efficacy of 683 lm/W: I = candela / 683 W/sr, E = lux / 683 W/m^2
//     (photometric_to_radiometric). So a 100 cd lamp 0.5 m away lights a white diffuse
//     surface to 400 / 683 = 0.59. The original value and unit are kept for `info`.
//   - Exposure: glTF viewers (the Khronos Sample Viewer, three.js) take candela and lux as
//     linear light at exposure 1 with a Lambertian BRDF of colour / pi, so a white surface
//     under E lux shows E / pi, and sample models are lit for that (PointLightIntensityTest's
//     lights are 1 cd). A scene whose lights are all a glTF file's is therefore seen at
//     log2(683 / pi) = 7.76 EV (default_exposure_ev, render's and view's default --exposure),
//     which shows exactly that; the lights keep their radiometric values, so the oracle and
//     every shadow method are untouched. Ambient level and emission are display quantities
//     (0.1 a dim ambient, 1 a white emitter, as in a staged scene at 0 EV) and are stored times
//     2^-EV (put_on_display_scale). Staged scenes stay at 0 EV.
//   - range (point and spot, 0 = none) multiplies the 1/d^2 falloff by the spec's window
//     clamp(1 - (d / range)^4, 0, 1).
//   - No light at all: dv::stage_scene (engine/scene/default_staging.h) once the camera is
//     set: a ground plane under the model when GltfImportOptions::staging asks for one,
//     a key spot light from above and to the left of the camera (the file's camera, else the
//     default one), irradiance 1 at the bounds' centre, its cone fitted to the model and its
//     shadow, and a dim fill along the view (log_info); not when
//     GltfImportOptions::default_lights is false (a JSON scene that imports the file stages it
//     itself).
// Materials (one per primitive; no material means glTF's default white material)
//   - color = baseColorFactor rgb; diffuse = 0.8; ambient stays 0.1.
//   - Phong from PBR roughness r: specular = 0.2 * (1 - r) + 0.04 (a dielectric's 4 % plus a
//     gloss term that fades with roughness); shininess = 2 / max(r^4, 1e-4) - 2 clamped to
//     [1, 512] (the Blinn-Phong exponent whose lobe matches a GGX lobe of alpha = r^2).
//   - baseColorTexture: its image (PNG or JPEG via stb_image: a data: URI, an external file in
//     the .gltf's folder, or a .glb buffer view; render/load/gltf_images.h says how URIs are
//     resolved) becomes a dv::Texture (8-bit RGBA, 16-bit images keep their high byte; RGB is
//     sRGB and decoded to linear when sampled), with its sampler's wrapS/wrapT (REPEAT,
//     CLAMP_TO_EDGE, MIRRORED_REPEAT) and magFilter (NEAREST, else bilinear; no mipmaps).
//     KHR_texture_transform (offset, rotation, scale, texCoord) on it becomes
//     Material::uv_transform, uv' = T R S uv with R = [[cos, sin], [-sin, cos]] (rows; the
//     extension's example picks the lower-left quadrant with it). An image that is missing,
//     refused (outside the model's folder) or undecodable does not refuse the model: one
//     warning names it and why, and its materials draw baseColorFactor as if untextured (their
//     coverage from the factor). The colour is baseColorFactor times the texel; the coverage a
//     below is computed per point from baseColorFactor alpha times the texel's alpha
//     (engine/scene/texture_sampling.h), in the oracle, the camera pass and every shadow
//     method. A primitive whose material has a texture but lacks its TEXCOORD set is an
//     InputError. normalTexture is ignored with one warning per file (vertex normals shade).
//   - Emission: emissiveFactor times KHR_materials_emissive_strength's emissiveStrength becomes
//     Material::emission (on the display scale, see "Exposure"), light the camera sees added
//     where the surface covers; it lights nothing else. An emissiveTexture (its sampler and
//     KHR_texture_transform) multiplies it by the texel's linear RGB; a primitive has one
//     TEXCOORD set, the base-colour texture's where there is one (an emissiveTexture naming
//     another set is read through it, with one warning naming the material); an unusable
//     emissive image drops the emission (the factor alone would light the whole surface, not
//     the texture's pattern), its image named in the warning.
//   - Coverage a = 1 for OPAQUE, the baseColorFactor alpha for BLEND, and 1 or 0 for MASK
//     (alpha >= alphaCutoff or not); t = KHR_materials_transmission transmissionFactor (0
//     without the extension). Material::alpha = a (1 - t) (the opaque part), ::transmission =
//     a t (the glass part), ::ior = KHR_materials_ior ior (default 1.5, at least 1). One
//     crossing lets through, per channel, T = (1 - a) + a t (1 - F) c with c the base colour
//     (white when the object has a KHR_materials_volume interior: the medium tints) and F
//     Schlick's Fresnel reflectance for ior at the crossing's angle
//     (engine/scene/surface_transmittance.h): glass of transmission 1 casts a partial shadow of
//     its colour (two crossings of clear glass: 0.92 at normal incidence), in the oracle, the
//     camera pass and every shadow method alike. In the camera image the glass part also shows
//     Phong highlights and reflects F of an ambient environment (a rim at grazing angles).
//   - KHR_materials_volume: thicknessFactor 0 (the default) is thin-walled: no interior.
//     thicknessFactor > 0 gives a constant interior with sigma = -ln(c) / d per channel from
//     attenuationColor c (default [1,1,1], channels clamped to >= 1e-6) and
//     attenuationDistance d (default +infinity, giving sigma 0): Interior::sigma their mean,
//     Interior::sigma_tint the ratios (exactly [1,1,1] for a grey medium). The oracle, the
//     camera pass and the shadows attenuate each channel by its own extinction (the DSM
//     storages carry the mean and a colour side channel the rest, engine/dsm/dsm_colour.h),
//     so a red medium casts a red shadow. An object with an interior must have a closed
//     mesh; dv::validate_scene, called at the end, reports open edges.
//   - Factors outside their glTF ranges ([0,1] colours, roughness, transmission; d > 0;
//     thickness >= 0) or of the wrong JSON type are InputErrors naming the material.
// The scene must contain at least one triangle; scene.source is set to the path.
#pragma once

#include <string>

#include "engine/scene/default_staging.h"

namespace dv {

// Luminous efficacy the KHR_lights_punctual spec uses to relate its photometric units to
// radiometric ones (lm/W).
inline constexpr double kLumensPerWatt = 683.0;

// candela -> W/sr (point, spot) or lux -> W/m^2 (directional): photometric / 683.
double photometric_to_radiometric(double photometric);

// log2(683 / pi) = 7.76: at this exposure a white Lambertian surface under E lux shows E / pi,
// as glTF viewers show photometric lights (see "Units" above).
double photometric_exposure_ev();

// photometric_exposure_ev() when the scene has lights and every one came from a glTF file
// (Light::source_unit set), else 0: the exposure its units are meant to be seen at.
double default_exposure_ev(const Scene& scene);

// Ambient level and emission are display quantities (0.1 is a dim ambient, an emission of 1 a
// white pixel, before the tone curve): a scene seen at exposure EV stores them times 2^-EV.
// Multiplies them by 2^ev.
void put_on_display_scale(Material& material, double ev);

struct GltfImportOptions {
  bool default_lights = true;  // stage the scene (dv::stage_scene) when the file has no light
  // The staged scene's ground plane: none here; load_scene passes the command's choice (a
  // ground by default).
  StagingOptions staging{.ground = GroundPlane::off};
};

// Loads a .gltf or .glb file as described above; throws InputError naming the file.
Scene load_gltf_scene(const std::string& path, const GltfImportOptions& options = {});

// True when the path ends in .gltf or .glb (any letter case).
bool is_gltf_file(const std::string& path);

}  // namespace dv
