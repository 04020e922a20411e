// glTF materials onto deepvox's: Phong parameters from PBR, coverage and transmission, ior,
// KHR_materials_volume interiors and the base-colour texture with KHR_texture_transform
// (mapping documented in render/load/gltf_import.h), and the checks every glTF reader shares.
// Split from gltf_import.cpp, which keeps nodes, meshes, lights, cameras and images.
#pragma once

#include <string>

#include <tiny_gltf.h>

#include "engine/scene/scene.h"

namespace dv::gltf {

// Phong material and interior of one glTF material (mapping documented in gltf_import.h); a
// base-colour texture by its glTF index (the importer turns it into a scene texture) and the
// TEXCOORD set it reads.
struct MappedMaterial {
  Material material;
  Interior interior;
  int gltf_texture = -1;
  int texcoord = 0;
  // The emissiveTexture's glTF texture index (-1: none) and the TEXCOORD set it names.
  int gltf_emissive_texture = -1;
  int emissive_texcoord = 0;
};

// The extension object `name` of an extension map, or nullptr.
const tinygltf::Value* find_extension(const tinygltf::ExtensionMap& extensions, const char* name);

// Throws InputError(where, problem) unless ok.
void require(bool ok, const std::string& where, const std::string& problem);

MappedMaterial map_gltf_material(const tinygltf::Material& m, const std::string& where);

}  // namespace dv::gltf
