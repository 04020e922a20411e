// Test helper that writes small glTF files: a JSON document built with nlohmann::json plus one
// binary buffer, saved as .gltf with a base64 data: URI, as .gltf with an external .bin, or as
// a .glb assembled byte by byte. Also a scratch directory per test.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

namespace dv::test {

using nlohmann::json;

inline std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t n = uint32_t(bytes[i]) << 16;
    if (i + 1 < bytes.size()) n |= uint32_t(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) n |= uint32_t(bytes[i + 2]);
    out += alphabet[(n >> 18) & 63];
    out += alphabet[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? alphabet[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? alphabet[n & 63] : '=';
  }
  return out;
}

inline void write_bytes(const std::filesystem::path& path, const std::vector<unsigned char>& b) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// A fresh directory under the system temp dir, removed when the test ends.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("deepvox_gltf_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

class GltfBuilder {
 public:
  json doc =
      json{{"asset", {{"version", "2.0"}}}, {"scene", 0}, {"scenes", {{{"nodes", json::array()}}}}};
  std::vector<unsigned char> bin;

  // Appends raw bytes (4-byte aligned) as a new buffer view; returns its index.
  int add_view(const void* data, size_t size) {
    while (bin.size() % 4) bin.push_back(0);
    size_t offset = bin.size();
    bin.resize(offset + size);
    std::memcpy(bin.data() + offset, data, size);
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}});
    return int(doc["bufferViews"].size()) - 1;
  }
  int add_accessor(int view, int component_type, size_t count, const std::string& type) {
    doc["accessors"].push_back({{"bufferView", view},
                                {"componentType", component_type},
                                {"count", count},
                                {"type", type}});
    return int(doc["accessors"].size()) - 1;
  }
  int add_positions(const std::vector<float>& xyz) {
    return add_accessor(add_view(xyz.data(), xyz.size() * 4), 5126, xyz.size() / 3, "VEC3");
  }
  int add_indices(const std::vector<uint16_t>& indices) {
    return add_accessor(add_view(indices.data(), indices.size() * 2), 5123, indices.size(),
                        "SCALAR");
  }
  // A mesh with one primitive; returns the mesh index.
  int add_mesh(json primitive) {
    doc["meshes"].push_back({{"primitives", json::array({std::move(primitive)})}});
    return int(doc["meshes"].size()) - 1;
  }
  int add_node(json node, bool root = true) {
    doc["nodes"].push_back(std::move(node));
    int index = int(doc["nodes"].size()) - 1;
    if (root) doc["scenes"][0]["nodes"].push_back(index);
    return index;
  }
  int add_material(json material) {
    doc["materials"].push_back(std::move(material));
    return int(doc["materials"].size()) - 1;
  }
  int add_light(json light) {
    doc["extensions"]["KHR_lights_punctual"]["lights"].push_back(std::move(light));
    return int(doc["extensions"]["KHR_lights_punctual"]["lights"].size()) - 1;
  }
  void use_extension(const std::string& name, bool required = false) {
    doc["extensionsUsed"].push_back(name);
    if (required) doc["extensionsRequired"].push_back(name);
  }

  std::string write_gltf(const std::string& path) {
    json d = with_buffer("data:application/octet-stream;base64," + base64(bin));
    write_text(path, d.dump(1));
    return path;
  }
  std::string write_gltf_external_bin(const std::string& path, const std::string& bin_name) {
    write_bytes(std::filesystem::path(path).parent_path() / bin_name, bin);
    write_text(path, with_buffer(bin_name).dump());
    return path;
  }
  std::vector<unsigned char> glb_bytes() const {
    std::string text = with_buffer("").dump();
    while (text.size() % 4) text += ' ';
    std::vector<unsigned char> body = bin;
    while (body.size() % 4) body.push_back(0);
    std::vector<unsigned char> out;
    auto raw = [&](const void* data, size_t size) {
      size_t at = out.size();
      out.resize(at + size);
      std::memcpy(out.data() + at, data, size);
    };
    auto u32 = [&](uint32_t v) {
      for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
    };
    raw("glTF", 4);
    u32(2);
    u32(uint32_t(12 + 8 + text.size() + 8 + body.size()));
    u32(uint32_t(text.size()));
    u32(0x4E4F534A);  // "JSON"
    raw(text.data(), text.size());
    u32(uint32_t(body.size()));
    u32(0x004E4942);  // "BIN\0"
    raw(body.data(), body.size());
    return out;
  }

 private:
  json with_buffer(const std::string& uri) const {
    json d = doc;
    if (!bin.empty()) {
      d["buffers"] = json::array({{{"byteLength", bin.size()}}});
      if (!uri.empty()) d["buffers"][0]["uri"] = uri;
    }
    return d;
  }
};

// A node holding the unit quad (0,0,0)-(1,1,0) facing +z with `material`, two triangles with
// UNSIGNED_SHORT indices and, with `texcoords`, TEXCOORD_0 (u, v) = (x, 1 - y); its index.
inline int add_quad_node(GltfBuilder& b, const json& material, bool texcoords) {
  const std::vector<float> xyz = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::vector<float> uv = {0, 1, 1, 1, 1, 0, 0, 0};
  const std::vector<uint16_t> idx = {0, 1, 2, 0, 2, 3};
  json attributes = {{"POSITION", b.add_positions(xyz)}};
  if (texcoords)
    attributes["TEXCOORD_0"] =
        b.add_accessor(b.add_view(uv.data(), uv.size() * 4), 5126, 4, "VEC2");
  return b.add_node({{"mesh", b.add_mesh({{"attributes", attributes},
                                          {"indices", b.add_indices(idx)},
                                          {"material", b.add_material(material)}})}});
}

// The unit cube [-1,1]^3 as an exporter writes it: 24 vertices (4 per face, split at the
// normal seams) and 12 outward-facing triangles with UNSIGNED_SHORT indices.
inline int add_box_mesh(GltfBuilder& b, json extra_primitive_fields = json::object()) {
  std::vector<float> xyz;
  std::vector<uint16_t> idx;
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign = -1; sign <= 1; sign += 2) {
      int u = (axis + 1) % 3, v = (axis + 2) % 3;
      uint16_t base = uint16_t(xyz.size() / 3);
      float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (auto& c : corners) {
        float p[3];
        p[axis] = float(sign);
        p[u] = c[0];
        p[v] = c[1];
        xyz.insert(xyz.end(), p, p + 3);
      }
      // (u, v, axis) is right-handed, so counter-clockwise in (u, v) faces +axis.
      if (sign > 0)
        idx.insert(idx.end(), {base, uint16_t(base + 1), uint16_t(base + 2), base,
                               uint16_t(base + 2), uint16_t(base + 3)});
      else
        idx.insert(idx.end(), {base, uint16_t(base + 2), uint16_t(base + 1), base,
                               uint16_t(base + 3), uint16_t(base + 2)});
    }
  }
  json prim = {{"attributes", {{"POSITION", b.add_positions(xyz)}}},
               {"indices", b.add_indices(idx)}};
  prim.update(extra_primitive_fields);
  return b.add_mesh(prim);
}

}  // namespace dv::test
