// glTF 2.0 import (.gltf with embedded or external buffers, and .glb) into deepvox's scene
// model, so scenes made in Blender & co. can be rendered and shadowed. tinygltf parses the file
// (compiled in io/gltf_impl.cpp); this importer validates everything it reads and maps it as
// documented below. The README points here for the mapping.
//
// How glTF maps onto dv::Scene
// ----------------------------
// Files and errors
//   - The file is read whole; bytes starting with "glTF" are parsed as GLB, anything else as
//     JSON. Missing or empty files, malformed JSON, a truncated or corrupt .glb, a bad buffer
//     URI: dv::InputError naming the file. tinygltf's own warnings become dv::log_warning.
//   - extensionsRequired may only name KHR_lights_punctual, KHR_materials_transmission,
//     KHR_materials_volume, KHR_materials_emissive_strength and KHR_texture_transform (the last
//     two change nothing here: deepvox has no emission and reads no textures). Any other
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
//     (glTF splits them at normal seams) so closed shapes are closed by index. A primitive
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
//   - No camera: fov 45 degrees, looking at the centre of the world bounds from the +Z side,
//     far enough that the bounding sphere fits the vertical field of view.
// Lights (KHR_lights_punctual, attached to nodes)
//   - Position = node origin; a light shines along its node's local -Z. spot -> spot with
//     cutoff_deg = outerConeAngle (default pi/4) and penumbra_deg = outer - inner cone angle,
//     both in degrees; point -> omni; directional -> directional. color and intensity
//     (default 1) are copied (glTF units: candela, lux for directional); range is ignored.
//   - No light at all: one omni light above the scene bounds (log_info), at height r above
//     the top, r the bounding-sphere radius, with intensity d^2 (d its distance to the bounds
//     centre) so the irradiance it gives at the centre is 1.
// Materials (one per primitive; no material means glTF's default white material)
//   - color = baseColorFactor rgb; diffuse = 0.8; ambient stays 0.1.
//   - Phong from PBR roughness r: specular = 0.2 * (1 - r) + 0.04 (a dielectric's 4 % plus a
//     gloss term that fades with roughness); shininess = 2 / max(r^4, 1e-4) - 2 clamped to
//     [1, 512] (the Blinn-Phong exponent whose lobe matches a GGX lobe of alpha = r^2).
//   - Surface alpha (opacity per crossing): coverage a times (1 - t). a = 1 for OPAQUE, the
//     baseColorFactor alpha for BLEND, and 1 or 0 for MASK (alpha >= alphaCutoff or not);
//     t = KHR_materials_transmission transmissionFactor (0 without the extension). So
//     transmission 0.25 gives alpha 0.75, and a BLEND material without it its factor's alpha.
//   - KHR_materials_volume: thicknessFactor 0 (the default) is thin-walled: no interior.
//     thicknessFactor > 0 gives a constant interior with sigma = -ln(c) / d per channel from
//     attenuationColor c (default [1,1,1], channels clamped to >= 1e-6) and
//     attenuationDistance d (default +infinity, giving sigma 0). deepvox media are grey: when
//     the channels' sigmas differ their mean is used and a warning is logged once per
//     material. An object with an interior must have a closed mesh; dv::validate_scene, called
//     at the end, reports open edges.
//   - Factors outside their glTF ranges ([0,1] colours, roughness, transmission; d > 0;
//     thickness >= 0) or of the wrong JSON type are InputErrors naming the material.
// The scene must contain at least one triangle; scene.source is set to the path.
#pragma once

#include <string>

#include "scene/scene.h"

namespace dv {

// Loads a .gltf or .glb file as described above; throws InputError naming the file.
Scene load_gltf_scene(const std::string& path);

// True when the path ends in .gltf or .glb (any letter case).
bool is_gltf_file(const std::string& path);

}  // namespace dv
