// glTF 2.0 import: tinygltf parses the file, this file validates every index, accessor and
// factor it uses and maps nodes, primitives, cameras, punctual lights and materials onto
// dv::Scene as documented in render/load/gltf_import.h.
#include "render/load/gltf_import.h"

#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "core/log.h"
#include "core/text.h"
#include "engine/scene/default_staging.h"
#include "engine/scene/mesh_topology.h"
#include "render/load/gltf_accessors.h"
#include "render/load/gltf_images.h"
#include "render/load/gltf_materials.h"

namespace dv {
namespace {

using gltf::AccessorKind;
using gltf::AccessorView;
using gltf::assemble_triangles;
using gltf::checked_accessor;
using gltf::find_extension;
using gltf::map_gltf_material;
using gltf::MappedMaterial;
using gltf::read_indices;
using gltf::read_texcoords;
using gltf::read_vec3s;
using gltf::require;

using tinygltf::Model;

constexpr double kPi = 3.14159265358979323846;

double degrees(double radians) {
  return radians * 180.0 / kPi;
}

std::string quoted_name(const std::string& name, const char* kind, int index) {
  return name.empty() ? std::string(kind) + " " + std::to_string(index)
                      : std::string(kind) + " " + std::to_string(index) + " '" + name + "'";
}

void warn_lines(const std::string& file, const std::string& text) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (!line.empty()) log_warning(file + ": " + line);
  }
}

std::vector<unsigned char> read_whole_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path, "file not found (or not a regular file)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open file");
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path, "read error");
  if (bytes.empty()) throw InputError(path, "file is empty");
  if (bytes.size() >= std::numeric_limits<uint32_t>::max())
    throw InputError(path, "file is too large for glTF (4 GiB or more)");
  return bytes;
}

uint32_t read_le32(const unsigned char* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

void check_glb_header(const std::string& path, const std::vector<unsigned char>& bytes) {
  if (bytes.size() < 20)
    throw InputError(path, "truncated .glb: " + std::to_string(bytes.size()) +
                               " bytes, but the header and JSON chunk header need 20");
  uint32_t version = read_le32(&bytes[4]);
  uint32_t length = read_le32(&bytes[8]);
  if (version != 2) throw InputError(path, "GLB version " + std::to_string(version) + ", not 2");
  if (length > bytes.size())
    throw InputError(path, "truncated .glb: the header declares " + std::to_string(length) +
                               " bytes but the file has " + std::to_string(bytes.size()));
}

// Parses the file; embedded images that cannot be decoded go to `undecodable`, not an error.
Model parse_model(const std::string& path, gltf::ImageFailures& undecodable) {
  std::vector<unsigned char> bytes = read_whole_file(path);
  bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  if (!binary && lowercase_extension(path) == ".glb")
    throw InputError(path, "not a binary glTF: the file does not start with 'glTF'");
  if (binary) check_glb_header(path, bytes);

  std::string base_dir = std::filesystem::path(path).parent_path().string();
  if (base_dir.empty()) base_dir = ".";
  tinygltf::TinyGLTF loader;
  gltf::install_image_decoder(loader, undecodable);
  gltf::BufferFiles buffer_files{base_dir, {}};
  gltf::install_buffer_policy(loader, buffer_files);
  Model model;
  std::string err, warn;
  bool ok = false;
  try {
    unsigned int size = static_cast<unsigned int>(bytes.size());
    ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), size, base_dir)
                : loader.LoadASCIIFromString(&model, &err, &warn,
                                             reinterpret_cast<const char*>(bytes.data()), size,
                                             base_dir);
  } catch (const std::exception& e) {
    throw InputError(path, std::string("cannot load glTF: ") + e.what());
  }
  if (!ok) {
    std::string problem;  // tinygltf's message lines, joined
    std::istringstream lines(err);
    for (std::string line; std::getline(lines, line);)
      if (!line.empty()) problem += (problem.empty() ? "" : "; ") + line;
    std::string refused;  // the buffer policy's reasons first: they name the files
    for (const std::string& p : buffer_files.problems) refused += p + "; ";
    problem = refused + problem;
    throw InputError(path, std::string("cannot load ") + (binary ? ".glb" : "glTF") + ": " +
                               (problem.empty() ? "unknown error" : problem));
  }
  warn_lines(path, warn);
  warn_lines(path, err);
  // glTF 2.0 only: a later major version may change what the same keys mean.
  const std::string& version = model.asset.version;
  if (version.substr(0, 2) != "2." && version != "2")
    throw InputError(path, "glTF asset version '" + version + "', but only 2.x is read");
  return model;
}

void check_extensions(const std::string& path, const Model& model) {
  static const std::set<std::string> supported = {
      "KHR_lights_punctual", "KHR_materials_transmission",      "KHR_materials_volume",
      "KHR_materials_ior",   "KHR_materials_emissive_strength", "KHR_texture_transform"};
  for (const std::string& name : model.extensionsRequired) {
    if (!supported.count(name))
      throw InputError(path, "required extension " + name + " is not supported by deepvox");
  }
  for (const std::string& name : model.extensionsUsed) {
    if (!supported.count(name))
      log_warning(path + ": extension " + name + " is not supported and is ignored");
  }
}

bool all_finite(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

dmat4 local_transform(const tinygltf::Node& node, const std::string& where) {
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16 || !all_finite(node.matrix))
      throw InputError(where, "matrix must have 16 finite numbers");
    return glm::make_mat4(node.matrix.data());  // both column-major
  }
  dmat4 m(1.0);
  if (!node.translation.empty()) {
    if (node.translation.size() != 3 || !all_finite(node.translation))
      throw InputError(where, "translation must have 3 finite numbers");
    m = glm::translate(m, glm::make_vec3(node.translation.data()));
  }
  if (!node.rotation.empty()) {
    const std::vector<double>& q = node.rotation;
    if (q.size() != 4 || !all_finite(q))
      throw InputError(where, "rotation must be a quaternion of 4 finite numbers");
    glm::dquat rotation(q[3], q[0], q[1], q[2]);  // glTF stores x, y, z, w
    if (glm::length(rotation) < 1e-12) throw InputError(where, "rotation quaternion is zero");
    m = m * glm::mat4_cast(glm::normalize(rotation));
  }
  if (!node.scale.empty()) {
    if (node.scale.size() != 3 || !all_finite(node.scale))
      throw InputError(where, "scale must have 3 finite numbers");
    m = glm::scale(m, glm::make_vec3(node.scale.data()));
  }
  return m;
}

class Importer {
 public:
  Importer(std::string path, Model& model, gltf::ImageFailures undecodable,
           const GltfImportOptions& options)
      : path_(std::move(path)),
        model_(model),
        undecodable_(std::move(undecodable)),
        options_(options) {}

  Scene run();

 private:
  int scene_mesh(int mesh_index, int primitive_index);
  void read_corner_attributes(const tinygltf::Primitive& prim, const std::string& of,
                              TriangleMesh& out, size_t vertex_count);
  const MappedMaterial& material(int index);
  int texture(int gltf_index, const std::string& where);
  bool image_usable(int image_index, const std::string& where);
  void add_node(int node_index, const dmat4& world);
  void add_light(const tinygltf::Node& node, const std::string& where, const dmat4& world);
  void finish_camera();
  std::string at(const std::string& what) const { return path_ + ": " + what; }

  std::string path_;
  Model& model_;
  gltf::ImageFailures undecodable_;  // embedded images that could not be decoded
  GltfImportOptions options_;
  Scene scene_;
  std::map<std::pair<int, int>, int> primitive_meshes_;  // (mesh, primitive) -> scene mesh or -1
  std::map<int, MappedMaterial> materials_;
  std::map<int, int> textures_;  // glTF texture -> scene texture, -1: its image is unusable
  std::map<int, bool> usable_images_;
  bool warned_normal_maps_ = false;
  bool has_camera_ = false;
  dmat4 camera_world_{1.0};
  int camera_index_ = -1;
  std::vector<char> visited_;  // nodes already placed (the hierarchy must be a tree)
};

int Importer::scene_mesh(int mesh_index, int primitive_index) {
  auto found = primitive_meshes_.find({mesh_index, primitive_index});
  if (found != primitive_meshes_.end()) return found->second;
  const tinygltf::Mesh& mesh = model_.meshes[size_t(mesh_index)];
  const tinygltf::Primitive& prim = mesh.primitives[size_t(primitive_index)];
  std::string mesh_name = quoted_name(mesh.name, "mesh", mesh_index);
  std::string where = at(mesh_name + " primitive " + std::to_string(primitive_index));
  int& result = primitive_meshes_[{mesh_index, primitive_index}];
  result = -1;
  if (prim.mode >= TINYGLTF_MODE_POINTS && prim.mode <= TINYGLTF_MODE_LINE_STRIP) {
    log_warning(where + ": points/lines primitive (mode " + std::to_string(prim.mode) +
                ") skipped: deepvox renders triangles only");
    return result;
  }
  if (prim.mode < TINYGLTF_MODE_TRIANGLES || prim.mode > TINYGLTF_MODE_TRIANGLE_FAN)
    throw InputError(where, "unknown primitive mode " + std::to_string(prim.mode));
  auto position = prim.attributes.find("POSITION");
  if (position == prim.attributes.end()) throw InputError(where, "primitive has no POSITION");
  std::string of = " of " + mesh_name + " primitive " + std::to_string(primitive_index);
  AccessorView pos_view =
      checked_accessor(model_, position->second, "POSITION" + of, path_, AccessorKind::position);
  std::vector<uint32_t> indices;
  if (prim.indices >= 0) {
    AccessorView idx_view =
        checked_accessor(model_, prim.indices, "indices" + of, path_, AccessorKind::indices);
    indices = read_indices(idx_view, pos_view.count);
  } else {
    indices.resize(pos_view.count);
    for (size_t i = 0; i < indices.size(); ++i) indices[i] = uint32_t(i);
  }
  TriangleMesh out;
  out.name = (mesh.name.empty() ? "mesh" + std::to_string(mesh_index) : mesh.name) +
             (mesh.primitives.size() > 1 ? "#" + std::to_string(primitive_index) : "");
  out.positions = read_vec3s(pos_view, "position");
  out.triangles = assemble_triangles(indices, prim.mode);
  read_corner_attributes(prim, of, out, pos_view.count);
  if (prim.mode == TINYGLTF_MODE_TRIANGLES && indices.size() % 3 != 0)
    log_warning(where + ": " + std::to_string(indices.size()) +
                " indices is not a multiple of 3; the last ones are ignored");
  if (out.triangles.empty()) {
    log_warning(where + ": primitive has no triangles; skipped");
    return result;
  }
  merge_duplicate_vertices(out);
  result = int(scene_.meshes.size());
  scene_.meshes.push_back(std::move(out));
  return result;
}

// The triangle corners' NORMALs, and their texture coordinates where the primitive's material
// has a base-colour texture (the TEXCOORD set it names); out.triangles index the primitive's
// vertices.
void Importer::read_corner_attributes(const tinygltf::Primitive& prim, const std::string& of,
                                      TriangleMesh& out, size_t vertex_count) {
  auto attribute = [&](const std::string& name, AccessorKind kind) {
    std::optional<AccessorView> view;
    auto found = prim.attributes.find(name);
    if (found == prim.attributes.end()) return view;
    view = checked_accessor(model_, found->second, name + of, path_, kind);
    if (view->count != vertex_count)
      throw InputError(view->where, name + " has " + std::to_string(view->count) +
                                        " elements but POSITION has " +
                                        std::to_string(vertex_count));
    return view;
  };
  if (const std::optional<AccessorView> normals = attribute("NORMAL", AccessorKind::normal)) {
    const std::vector<dvec3> n = read_vec3s(*normals, "normal");
    for (const u32vec3& t : out.triangles)
      for (int k = 0; k < 3; ++k) out.corner_normals.push_back(n[t[k]]);
  }
  const MappedMaterial& mapped = material(prim.material);
  if (mapped.gltf_texture < 0 && mapped.gltf_emissive_texture < 0) return;
  const std::string set = "TEXCOORD_" + std::to_string(mapped.texcoord);
  const std::optional<AccessorView> uvs = attribute(set, AccessorKind::texcoord);
  if (!uvs)
    throw InputError(
        at("material " + std::to_string(prim.material)),
        std::string(mapped.gltf_texture >= 0 ? "its base-colour texture" : "its emissive texture") +
            " reads " + set + ", which the primitive" + of + " does not have");
  const std::vector<dvec2> uv = read_texcoords(*uvs);
  for (const u32vec3& t : out.triangles)
    for (int k = 0; k < 3; ++k) out.corner_uvs.push_back(uv[t[k]]);
}

// Whether image `image_index` can be used; the first time it cannot (an embedded one that did
// not decode, an external file that is refused, missing or undecodable: read here,
// render/load/gltf_images.h), one warning at `where` names it and why.
bool Importer::image_usable(int image_index, const std::string& where) {
  auto known = usable_images_.find(image_index);
  if (known != usable_images_.end()) return known->second;
  tinygltf::Image& image = model_.images[size_t(image_index)];
  std::string problem;
  if (auto failed = undecodable_.find(image_index); failed != undecodable_.end()) {
    problem = failed->second;
  } else if (image.image.empty()) {
    std::filesystem::path folder = std::filesystem::path(path_).parent_path();
    if (folder.empty()) folder = ".";
    problem =
        image.uri.empty() ? "no image data" : gltf::read_external_image(image, image_index, folder);
  }
  if (!problem.empty())
    log_warning(where + ": " + problem + "; the materials using it draw their factors without it");
  return usable_images_.emplace(image_index, problem.empty()).first->second;
}

// The scene texture of glTF texture `gltf_index`: its image decoded to RGBA8 (16-bit images
// keep their high bytes) and its sampler's wrap modes and magnification filter (no mipmaps:
// minification filters are read as the magnification filter). -1, with one warning naming the
// image and why, when the image cannot be used: the materials then draw their factors.
int Importer::texture(int gltf_index, const std::string& where) {
  auto found = textures_.find(gltf_index);
  if (found != textures_.end()) return found->second;
  if (gltf_index < 0 || size_t(gltf_index) >= model_.textures.size())
    throw InputError(where, "base-colour texture " + std::to_string(gltf_index) +
                                " does not exist (the file has " +
                                std::to_string(model_.textures.size()) + " textures)");
  const tinygltf::Texture& src = model_.textures[size_t(gltf_index)];
  std::string texture_where = at(quoted_name(src.name, "texture", gltf_index));
  if (src.source < 0 || size_t(src.source) >= model_.images.size())
    throw InputError(texture_where, "image " + std::to_string(src.source) + " does not exist");
  const tinygltf::Image& image = model_.images[size_t(src.source)];
  std::string image_where =
      at(quoted_name(image.name.empty() ? image.uri : image.name, "image", src.source));
  if (!image_usable(src.source, image_where)) {
    textures_.emplace(gltf_index, -1);
    return -1;
  }
  const size_t texels = size_t(image.width) * size_t(image.height);
  const size_t bytes_per = size_t(image.bits / 8);
  if (image.component != 4 || (image.bits != 8 && image.bits != 16) ||
      image.image.size() != texels * 4 * bytes_per)
    throw InputError(image_where, "image decoded to an unexpected layout");
  Texture t;
  t.name = image.uri.empty() ? "image " + std::to_string(src.source) : image.uri;
  t.width = image.width;
  t.height = image.height;
  t.rgba.resize(texels * 4);
  for (size_t i = 0; i < texels * 4; ++i)
    t.rgba[i] = image.image[i * bytes_per + (bytes_per - 1)];  // little-endian: high byte last
  if (src.sampler >= 0) {
    if (size_t(src.sampler) >= model_.samplers.size())
      throw InputError(texture_where, "sampler " + std::to_string(src.sampler) + " does not exist");
    const tinygltf::Sampler& sampler = model_.samplers[size_t(src.sampler)];
    auto wrap = [&](int mode) {
      if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return TextureWrap::clamp;
      if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return TextureWrap::mirror;
      require(mode == TINYGLTF_TEXTURE_WRAP_REPEAT, texture_where,
              "unknown wrap mode " + std::to_string(mode));
      return TextureWrap::repeat;
    };
    t.wrap_s = wrap(sampler.wrapS);
    t.wrap_t = wrap(sampler.wrapT);
    const int filter = sampler.magFilter >= 0 ? sampler.magFilter : sampler.minFilter;
    const bool nearest = filter == TINYGLTF_TEXTURE_FILTER_NEAREST ||
                         filter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
                         filter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR;
    t.filter = nearest ? TextureFilter::nearest : TextureFilter::bilinear;
  }
  const int index = int(scene_.textures.size());
  scene_.textures.push_back(std::move(t));
  textures_.emplace(gltf_index, index);
  return index;
}

const MappedMaterial& Importer::material(int index) {
  auto found = materials_.find(index);
  if (found != materials_.end()) return found->second;
  if (index >= 0 && size_t(index) >= model_.materials.size())
    throw InputError(at("material " + std::to_string(index)), "material index out of range");
  tinygltf::Material fallback;  // glTF's default material: white, rough, opaque
  const tinygltf::Material& m = index >= 0 ? model_.materials[size_t(index)] : fallback;
  std::string where = at(quoted_name(m.name, "material", index));
  MappedMaterial mapped = map_gltf_material(m, where);
  if (mapped.gltf_texture >= 0) {
    mapped.material.base_texture = texture(mapped.gltf_texture, where);
    if (mapped.material.base_texture < 0) {  // unusable image: the factor alone, as untextured
      tinygltf::Material untextured = m;
      untextured.pbrMetallicRoughness.baseColorTexture = tinygltf::TextureInfo();
      mapped = map_gltf_material(untextured, where);
    }
  }
  if (mapped.gltf_emissive_texture >= 0) {
    mapped.material.emissive_texture = texture(mapped.gltf_emissive_texture, where);
    if (mapped.material.emissive_texture < 0) {  // unusable image (named): no emission
      mapped.material.emission = dvec3(0.0);
      mapped.gltf_emissive_texture = -1;
    } else if (mapped.gltf_texture < 0) {
      mapped.texcoord = mapped.emissive_texcoord;  // the primitive's one TEXCOORD set
    } else if (mapped.emissive_texcoord != mapped.texcoord) {
      log_warning(where + ": emissiveTexture reads TEXCOORD_" +
                  std::to_string(mapped.emissive_texcoord) + ", the base-colour texture TEXCOORD_" +
                  std::to_string(mapped.texcoord) +
                  "; deepvox reads one set per primitive, so the emission is drawn through "
                  "TEXCOORD_" +
                  std::to_string(mapped.texcoord));
    }
  }
  if (m.normalTexture.index >= 0 && !warned_normal_maps_) {
    warned_normal_maps_ = true;
    log_warning(where +
                ": normalTexture is ignored (deepvox does not read normal maps); the "
                "surface is shaded with its vertex normals");
  }
  return materials_.emplace(index, std::move(mapped)).first->second;
}

void Importer::add_node(int root, const dmat4& root_world) {
  std::vector<std::pair<int, dmat4>> stack{{root, root_world}};
  while (!stack.empty()) {
    auto [index, parent] = stack.back();
    stack.pop_back();
    if (index < 0 || size_t(index) >= model_.nodes.size())
      throw InputError(at("node " + std::to_string(index)), "node index out of range");
    if (visited_[size_t(index)])
      throw InputError(at("node " + std::to_string(index)),
                       "node is reached twice: the node hierarchy must be a tree");
    visited_[size_t(index)] = 1;
    const tinygltf::Node& node = model_.nodes[size_t(index)];
    std::string node_name = quoted_name(node.name, "node", index);
    dmat4 world = parent * local_transform(node, at(node_name));
    if (node.mesh >= 0) {
      if (size_t(node.mesh) >= model_.meshes.size())
        throw InputError(at(node_name),
                         "mesh index " + std::to_string(node.mesh) + " out of range");
      const tinygltf::Mesh& mesh = model_.meshes[size_t(node.mesh)];
      for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        int mesh_id = scene_mesh(node.mesh, int(p));
        if (mesh_id < 0) continue;
        const MappedMaterial& mat = material(mesh.primitives[p].material);
        Object obj;
        obj.name = (node.name.empty() ? "node" + std::to_string(index) : node.name) +
                   (mesh.primitives.size() > 1 ? "#" + std::to_string(p) : "");
        obj.mesh = mesh_id;
        obj.transform = world;
        obj.material = mat.material;
        obj.interior = mat.interior;
        scene_.objects.push_back(std::move(obj));
      }
    }
    if (node.camera >= 0) {
      if (size_t(node.camera) >= model_.cameras.size())
        throw InputError(at(node_name),
                         "camera index " + std::to_string(node.camera) + " out of range");
      if (model_.cameras[size_t(node.camera)].type != "perspective") {
        log_warning(at(node_name) + ": orthographic camera ignored");
      } else if (!has_camera_) {
        has_camera_ = true;
        camera_world_ = world;
        camera_index_ = node.camera;
      }
    }
    add_light(node, at(node_name), world);
    for (auto child = node.children.rbegin(); child != node.children.rend(); ++child)
      stack.emplace_back(*child, world);
  }
}

void Importer::add_light(const tinygltf::Node& node, const std::string& where, const dmat4& world) {
  const tinygltf::Value* ext = find_extension(node.extensions, "KHR_lights_punctual");
  if (!ext) return;
  const tinygltf::Value& ref = ext->Has("light") ? ext->Get("light") : tinygltf::Value();
  double ref_number = ref.IsNumber() ? ref.GetNumberAsDouble() : -1.0;
  if (!(ref_number >= 0.0 && ref_number < double(model_.lights.size()) &&
        ref_number == std::floor(ref_number)))
    throw InputError(where,
                     "KHR_lights_punctual light index is missing or out of range (the "
                     "file has " +
                         std::to_string(model_.lights.size()) + " lights)");
  int index = int(ref_number);
  const tinygltf::Light& src = model_.lights[size_t(index)];
  std::string light_where = at(quoted_name(src.name, "light", index));
  Light light;
  light.position = dvec3(world[3]);
  dvec3 direction = glm::dmat3(world) * dvec3(0.0, 0.0, -1.0);
  require(glm::length(direction) > 1e-12, where, "node transform collapses the light direction");
  light.direction = glm::normalize(direction);
  if (src.type == "spot") {
    double inner = src.spot.innerConeAngle, outer = src.spot.outerConeAngle;
    require(std::isfinite(inner) && std::isfinite(outer) && inner >= 0.0 && inner <= outer &&
                outer > 0.0 && outer <= 0.5 * kPi + 1e-9,
            light_where, "spot cone angles need 0 <= innerConeAngle <= outerConeAngle <= pi/2");
    light.type = LightType::spot;
    light.cutoff_deg = std::min(degrees(outer), 90.0);
    // cos_inner = cos(cutoff - penumbra) = cos(innerConeAngle): the spec's falloff window.
    light.penumbra_deg = degrees(outer - inner);
  } else if (src.type == "point") {
    light.type = LightType::omni;
  } else if (src.type == "directional") {
    light.type = LightType::directional;
  } else {
    throw InputError(light_where, "unknown light type '" + src.type + "'");
  }
  if (!src.color.empty()) {
    require(src.color.size() == 3 && all_finite(src.color) &&
                std::all_of(src.color.begin(), src.color.end(), [](double c) { return c >= 0; }),
            light_where, "color must be 3 numbers >= 0");
    light.color = dvec3(src.color[0], src.color[1], src.color[2]);
  }
  require(std::isfinite(src.intensity) && src.intensity >= 0.0, light_where,
          "intensity must be a finite number >= 0");
  require(std::isfinite(src.range) && src.range >= 0.0, light_where,
          "range must be a finite number >= 0 (0: no range)");
  light.intensity = photometric_to_radiometric(src.intensity);
  light.source_intensity = src.intensity;
  light.source_unit = light.type == LightType::directional ? "lx" : "cd";
  light.gltf_cone = light.type == LightType::spot;
  light.range = light.type == LightType::directional ? 0.0 : src.range;
  scene_.lights.push_back(light);
}

void Importer::finish_camera() {
  Aabb box = world_bounds(scene_);
  Camera& cam = scene_.camera;
  cam.width = 640;
  cam.height = 480;
  cam.up = dvec3(0.0, 1.0, 0.0);
  if (!has_camera_) {
    cam = default_camera(box);
    return;
  }
  const tinygltf::Camera& src = model_.cameras[size_t(camera_index_)];
  const tinygltf::PerspectiveCamera& p = src.perspective;
  std::string where = at(quoted_name(src.name, "camera", camera_index_));
  require(p.yfov > 0.0 && p.yfov < kPi, where, "yfov must lie in (0, pi) radians");
  require(p.znear > 0.0 && std::isfinite(p.znear), where, "znear must be a finite number > 0");
  require(p.aspectRatio >= 0.0 && std::isfinite(p.aspectRatio), where, "aspectRatio must be > 0");
  glm::dmat3 basis(camera_world_);
  dvec3 forward = basis * dvec3(0.0, 0.0, -1.0);
  dvec3 up = basis * dvec3(0.0, 1.0, 0.0);
  require(glm::length(glm::cross(forward, up)) > 1e-12, where,
          "the camera node's transform is degenerate");
  cam.position = dvec3(camera_world_[3]);
  double distance = glm::length(box.center() - cam.position);
  if (!(distance > 1e-9)) distance = 1.0;
  cam.target = cam.position + glm::normalize(forward) * distance;
  cam.up = glm::normalize(up);
  cam.fov_deg = degrees(p.yfov);
  if (p.aspectRatio > 0.0)
    cam.height = int(std::clamp(std::round(640.0 / p.aspectRatio), 0.0, 1e6));
  cam.near_plane = p.znear;
}

Scene Importer::run() {
  if (model_.scenes.empty()) throw InputError(path_, "the file has no scenes");
  int scene_index = model_.defaultScene >= 0 ? model_.defaultScene : 0;
  if (size_t(scene_index) >= model_.scenes.size())
    throw InputError(path_, "default scene " + std::to_string(scene_index) + " does not exist");
  visited_.assign(model_.nodes.size(), 0);
  for (int root : model_.scenes[size_t(scene_index)].nodes) add_node(root, dmat4(1.0));
  if (scene_.objects.empty())
    throw InputError(path_, "the scene has no triangle primitives: nothing to render");
  std::set<int> with_interior;
  for (const Object& obj : scene_.objects)
    if (obj.interior.kind != InteriorKind::none) with_interior.insert(obj.mesh);
  for (int mesh : with_interior) {
    if (is_closed(scene_.meshes[size_t(mesh)])) orient_outward(scene_.meshes[size_t(mesh)]);
  }
  finish_camera();
  if (options_.default_lights && stage_scene(scene_, options_.staging))
    log_info(path_ + ": no lights in the file; added the default key and fill lights" +
             (scene_.objects.back().name == "ground" ? " and a ground plane" : ""));
  // The file's own lights are photometric: the scene is seen at the exposure that shows them as
  // glTF viewers do (0 when the lights are staged).
  const double exposure_ev = default_exposure_ev(scene_);
  for (Object& obj : scene_.objects) put_on_display_scale(obj.material, -exposure_ev);
  scene_.source = path_;
  validate_scene(scene_);
  return std::move(scene_);
}

}  // namespace

Scene load_gltf_scene(const std::string& path, const GltfImportOptions& options) {
  gltf::ImageFailures undecodable;
  Model model = parse_model(path, undecodable);
  check_extensions(path, model);
  return Importer(path, model, std::move(undecodable), options).run();
}

double photometric_to_radiometric(double photometric) {
  return photometric / kLumensPerWatt;
}

double photometric_exposure_ev() {
  return std::log2(kLumensPerWatt / kPi);
}

void put_on_display_scale(Material& material, double ev) {
  material.ambient *= std::exp2(ev);
  material.emission *= std::exp2(ev);
}

double default_exposure_ev(const Scene& scene) {
  const bool photometric =
      !scene.lights.empty() && std::all_of(scene.lights.begin(), scene.lights.end(),
                                           [](const Light& l) { return !l.source_unit.empty(); });
  return photometric ? photometric_exposure_ev() : 0.0;
}

bool is_gltf_file(const std::string& path) {
  const std::string ext = lowercase_extension(path);
  return ext == ".gltf" || ext == ".glb";
}

}  // namespace dv
