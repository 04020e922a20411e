// map_gltf_material and the shared checks (see gltf_materials.h).
#include "render/load/gltf_materials.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/error.h"

namespace dv::gltf {

const tinygltf::Value* find_extension(const tinygltf::ExtensionMap& extensions, const char* name) {
  auto found = extensions.find(name);
  return found == extensions.end() ? nullptr : &found->second;
}

void require(bool ok, const std::string& where, const std::string& problem) {
  if (!ok) throw InputError(where, problem);
}

namespace {

// A finite number field of an extension object, or `fallback` when absent.
double number_field(const tinygltf::Value& object, const char* key, double fallback,
                    const std::string& where) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& value = object.Get(key);
  if (!value.IsNumber() || !std::isfinite(value.GetNumberAsDouble()))
    throw InputError(where, std::string(key) + " must be a finite number");
  return value.GetNumberAsDouble();
}

bool unit_range(double v) {
  return v >= 0.0 && v <= 1.0;
}

dvec3 attenuation_color(const tinygltf::Value& volume, const std::string& where) {
  if (!volume.Has("attenuationColor")) return dvec3(1.0);
  const tinygltf::Value& array = volume.Get("attenuationColor");
  dvec3 color(1.0);
  bool ok = array.IsArray() && array.ArrayLen() == 3;
  for (int i = 0; ok && i < 3; ++i) {
    ok = array.Get(i).IsNumber() && unit_range(array.Get(i).GetNumberAsDouble());
    if (ok) color[i] = array.Get(i).GetNumberAsDouble();
  }
  require(ok, where, "attenuationColor must be 3 numbers in [0, 1]");
  return color;
}

// Constant interior from KHR_materials_volume, or none when thin-walled.
Interior volume_interior(const tinygltf::Value& volume, const std::string& where) {
  Interior interior;
  double thickness = number_field(volume, "thicknessFactor", 0.0, where);
  require(thickness >= 0.0, where, "thicknessFactor must be >= 0");
  dvec3 color = attenuation_color(volume, where);
  double distance =
      number_field(volume, "attenuationDistance", std::numeric_limits<double>::infinity(), where);
  require(distance > 0.0, where, "attenuationDistance must be > 0");
  if (thickness == 0.0) return interior;  // thin-walled: no medium inside
  dvec3 sigma(0.0);
  if (std::isfinite(distance)) sigma = -glm::log(glm::max(color, dvec3(1e-6))) / distance;
  interior.kind = InteriorKind::constant;
  const bool grey = sigma.x == sigma.y && sigma.y == sigma.z;  // tint exactly 1 (no colour)
  interior.sigma = grey ? sigma.x : (sigma.x + sigma.y + sigma.z) / 3.0;
  if (interior.sigma > 0.0 && !grey) interior.sigma_tint = sigma / interior.sigma;
  return interior;
}

// A texture reference's UV transform and TEXCOORD set.
struct TextureTransform {
  glm::dmat3 uv;
  int texcoord = 0;
};

// A 2-number array field of an extension object, or `fallback` when absent.
dvec2 pair_field(const tinygltf::Value& object, const char* key, dvec2 fallback,
                 const std::string& where) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& array = object.Get(key);
  bool ok = array.IsArray() && array.ArrayLen() == 2;
  for (int i = 0; ok && i < 2; ++i) {
    ok = array.Get(i).IsNumber() && std::isfinite(array.Get(i).GetNumberAsDouble());
    if (ok) fallback[i] = array.Get(i).GetNumberAsDouble();
  }
  require(ok, where, std::string(key) + " must be 2 finite numbers");
  return fallback;
}

// KHR_texture_transform on a texture reference: uv' = T(offset) R(rotation) S(scale) uv
// with R = [[cos, sin], [-sin, cos]] (rows): u' = u cos + v sin, v' = -u sin + v cos. The
// ratified extension writes R column-major as mat3(cos, -sin, 0, sin, cos, 0, 0, 0, 1); its
// example (offset [0, 1], rotation pi/2, scale 0.5 picks the image's lower-left quadrant, v
// pointing down) holds only with this sign. And its texCoord override.
TextureTransform read_texture_transform(const tinygltf::Value& ext, const std::string& where,
                                        int texcoord) {
  const dvec2 offset = pair_field(ext, "offset", dvec2(0.0), where);
  const dvec2 scale = pair_field(ext, "scale", dvec2(1.0), where);
  const double rotation = number_field(ext, "rotation", 0.0, where);
  const double c = std::cos(rotation), s = std::sin(rotation);
  const glm::dmat3 translate(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, offset.x, offset.y, 1.0);
  const glm::dmat3 rotate(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);  // columns, as glm takes them
  const glm::dmat3 scaling(scale.x, 0.0, 0.0, 0.0, scale.y, 0.0, 0.0, 0.0, 1.0);
  const double set = number_field(ext, "texCoord", double(texcoord), where);
  require(set >= 0.0 && set == std::floor(set) && set < 64.0, where,
          "texCoord must be a small integer >= 0");
  return {translate * rotate * scaling, int(set)};
}

// A texture reference's KHR_texture_transform (identity without one) and TEXCOORD set.
TextureTransform texture_transform(const tinygltf::TextureInfo& texture, const std::string& where) {
  if (const tinygltf::Value* ext = find_extension(texture.extensions, "KHR_texture_transform"))
    return read_texture_transform(*ext, where + ": KHR_texture_transform", texture.texCoord);
  return {glm::dmat3(1.0), texture.texCoord};
}

// emissiveFactor times KHR_materials_emissive_strength's emissiveStrength, on the scale glTF
// viewers display it (1: a pixel of 1 before the tone curve); the importer puts it on the
// scene's light scale; an emissiveTexture (mapped by the importer) multiplies it per texel.
void read_emission(const tinygltf::Material& m, const std::string& where, MappedMaterial& out) {
  const std::vector<double>& factor = m.emissiveFactor;
  if (factor.empty()) return;  // glTF's default material (tinygltf fills only parsed ones)
  require(factor.size() == 3 && std::all_of(factor.begin(), factor.end(), unit_range), where,
          "emissiveFactor must be 3 numbers in [0, 1]");
  double strength = 1.0;
  if (const tinygltf::Value* ext =
          find_extension(m.extensions, "KHR_materials_emissive_strength")) {
    const std::string ext_where = where + ": KHR_materials_emissive_strength";
    strength = number_field(*ext, "emissiveStrength", 1.0, ext_where);
    require(strength >= 0.0, ext_where, "emissiveStrength must be >= 0");
  }
  out.material.emission = dvec3(factor[0], factor[1], factor[2]) * strength;
  if (m.emissiveTexture.index < 0) return;
  out.gltf_emissive_texture = m.emissiveTexture.index;
  const TextureTransform t = texture_transform(m.emissiveTexture, where + ": emissiveTexture");
  out.material.emissive_uv_transform = t.uv;
  out.emissive_texcoord = t.texcoord;
}

}  // namespace

MappedMaterial map_gltf_material(const tinygltf::Material& m, const std::string& where) {
  MappedMaterial out;
  const std::vector<double>& base = m.pbrMetallicRoughness.baseColorFactor;
  require(base.size() == 4 && std::all_of(base.begin(), base.end(), unit_range), where,
          "baseColorFactor must be 4 numbers in [0, 1]");
  double roughness = m.pbrMetallicRoughness.roughnessFactor;
  require(unit_range(roughness), where, "roughnessFactor must lie in [0, 1]");
  out.material.color = dvec3(base[0], base[1], base[2]);
  out.material.diffuse = 0.8;
  out.material.specular = 0.2 * (1.0 - roughness) + 0.04;
  double r4 = roughness * roughness * roughness * roughness;
  out.material.shininess = clamp_value(2.0 / std::max(r4, 1e-4) - 2.0, 1.0, 512.0);

  double coverage = 1.0;
  if (m.alphaMode == "BLEND") {
    coverage = base[3];
    out.material.alpha_mode = AlphaMode::blend;
  } else if (m.alphaMode == "MASK") {
    require(std::isfinite(m.alphaCutoff) && m.alphaCutoff >= 0.0, where,
            "alphaCutoff must be a finite number >= 0");
    coverage = base[3] >= m.alphaCutoff ? 1.0 : 0.0;
    out.material.alpha_mode = AlphaMode::mask;
  } else {
    require(m.alphaMode == "OPAQUE", where, "alphaMode must be OPAQUE, MASK or BLEND");
  }
  out.material.alpha_cutoff = m.alphaCutoff;
  const tinygltf::TextureInfo& texture = m.pbrMetallicRoughness.baseColorTexture;
  if (texture.index >= 0) {
    // Coverage comes per point from the factor times the texel's alpha (texture_sampling.h).
    out.gltf_texture = texture.index;
    out.material.coverage_factor = base[3];
    coverage = 1.0;
    const TextureTransform t = texture_transform(texture, where);
    out.material.uv_transform = t.uv;
    out.texcoord = t.texcoord;
  }
  double transmission = 0.0;
  if (const tinygltf::Value* ext = find_extension(m.extensions, "KHR_materials_transmission")) {
    std::string ext_where = where + ": KHR_materials_transmission";
    transmission = number_field(*ext, "transmissionFactor", 0.0, ext_where);
    require(unit_range(transmission), ext_where, "transmissionFactor must lie in [0, 1]");
  }
  out.material.alpha = coverage * (1.0 - transmission);
  out.material.transmission = coverage * transmission;
  if (const tinygltf::Value* ext = find_extension(m.extensions, "KHR_materials_ior")) {
    std::string ext_where = where + ": KHR_materials_ior";
    out.material.ior = number_field(*ext, "ior", 1.5, ext_where);
    require(out.material.ior >= 1.0 && std::isfinite(out.material.ior), ext_where,
            "ior must be a finite number >= 1");
  }
  if (const tinygltf::Value* ext = find_extension(m.extensions, "KHR_materials_volume"))
    out.interior = volume_interior(*ext, where + ": KHR_materials_volume");
  read_emission(m, where, out);
  return out;
}

}  // namespace dv::gltf
