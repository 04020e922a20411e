// glTF accessors read safely: an accessor validated completely (index, component type, element
// type, byte ranges) before anything is read, then its elements as positions, normals, texture
// coordinates or indices, and index lists assembled into triangles. Split from gltf_import.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "core/math.h"

namespace dv::gltf {

// A validated accessor: element i starts at first + i * stride; `where` names it in messages.
struct AccessorView {
  std::string where;
  const unsigned char* first = nullptr;
  size_t stride = 0;
  size_t count = 0;
  int component_type = 0;
};

// What an accessor holds, for the type checks of checked_accessor.
enum class AccessorKind { position, indices, normal, texcoord };

// Validates accessor `index` completely (indices, types, byte ranges) before anything is read;
// InputError naming `path`, the accessor and its `role` otherwise.
AccessorView checked_accessor(const tinygltf::Model& model, int index, const std::string& role,
                              const std::string& path, AccessorKind kind);

// FLOAT VEC3 elements (positions, normals); `what` names one in messages.
std::vector<dvec3> read_vec3s(const AccessorView& view, const char* what);

// VEC2 texture coordinates: FLOAT, or normalized unsigned integers mapped to [0, 1].
std::vector<dvec2> read_texcoords(const AccessorView& view);

// Indices (UNSIGNED_BYTE, SHORT or INT), each checked against the vertex count.
std::vector<uint32_t> read_indices(const AccessorView& view, size_t vertex_count);

// Triangles of a TRIANGLES / TRIANGLE_STRIP / TRIANGLE_FAN index list (glTF 2.0 §3.7.2.1),
// dropping triangles that repeat a vertex.
std::vector<u32vec3> assemble_triangles(const std::vector<uint32_t>& idx, int mode);

}  // namespace dv::gltf
