// glTF accessors read safely (gltf_accessors.h).
#include "render/load/gltf_accessors.h"

#include <cmath>
#include <cstring>
#include <limits>

#include "core/error.h"

namespace dv::gltf {

using tinygltf::Model;

namespace {

int component_size(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

}  // namespace

// Validates accessor `index` completely (indices, types, byte ranges) before anything is read.
AccessorView checked_accessor(const Model& model, int index, const std::string& role,
                              const std::string& path, AccessorKind kind) {
  std::string where = path + ": accessor " + std::to_string(index) + " (" + role + ")";
  if (index < 0 || size_t(index) >= model.accessors.size())
    throw InputError(where, "accessor index out of range (the file has " +
                                std::to_string(model.accessors.size()) + " accessors)");
  const tinygltf::Accessor& acc = model.accessors[size_t(index)];
  if (acc.sparse.isSparse) throw InputError(where, "sparse accessors are not supported");
  int components = 1;
  if (kind == AccessorKind::position || kind == AccessorKind::normal) {
    components = 3;
    if (acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || acc.type != TINYGLTF_TYPE_VEC3)
      throw InputError(where, std::string(kind == AccessorKind::normal ? "NORMAL" : "POSITION") +
                                  " must be a FLOAT VEC3 accessor");
  } else if (kind == AccessorKind::texcoord) {
    components = 2;
    const int type = acc.componentType;
    if (acc.type != TINYGLTF_TYPE_VEC2 ||
        !(type == TINYGLTF_COMPONENT_TYPE_FLOAT ||
          (acc.normalized && (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                              type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT))))
      throw InputError(where,
                       "TEXCOORD must be a VEC2 accessor of FLOAT or normalized UNSIGNED_BYTE or "
                       "UNSIGNED_SHORT");
  } else if (acc.type != TINYGLTF_TYPE_SCALAR || component_size(acc.componentType) == 0 ||
             acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
    throw InputError(where,
                     "indices must be an UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT "
                     "SCALAR accessor");
  }
  if (acc.bufferView < 0 || size_t(acc.bufferView) >= model.bufferViews.size())
    throw InputError(where, "buffer view " + std::to_string(acc.bufferView) +
                                " does not exist (the file has " +
                                std::to_string(model.bufferViews.size()) + ")");
  const tinygltf::BufferView& view = model.bufferViews[size_t(acc.bufferView)];
  std::string view_name = "buffer view " + std::to_string(acc.bufferView);
  if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
    throw InputError(where, view_name + " refers to buffer " + std::to_string(view.buffer) +
                                ", which does not exist");
  const std::vector<unsigned char>& data = model.buffers[size_t(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    throw InputError(where, view_name + " (byteOffset " + std::to_string(view.byteOffset) +
                                ", byteLength " + std::to_string(view.byteLength) +
                                ") runs past the end of buffer " + std::to_string(view.buffer) +
                                " (" + std::to_string(data.size()) + " bytes)");
  size_t element = size_t(component_size(acc.componentType)) * size_t(components);
  size_t stride = view.byteStride ? view.byteStride : element;
  if (stride < element)
    throw InputError(where, view_name + " byteStride " + std::to_string(stride) +
                                " is smaller than the element size " + std::to_string(element));
  size_t length = view.byteLength;
  if (acc.count > 0 && (element > length || acc.byteOffset > length - element ||
                        (acc.count - 1) > (length - element - acc.byteOffset) / stride))
    throw InputError(where, std::to_string(acc.count) + " elements of " + std::to_string(element) +
                                " bytes (stride " + std::to_string(stride) + ") from byteOffset " +
                                std::to_string(acc.byteOffset) + " run past the end of " +
                                view_name + " (byteLength " + std::to_string(length) + ")");
  AccessorView out;
  out.where = where;
  out.first = data.data() + view.byteOffset + (acc.count > 0 ? acc.byteOffset : 0);
  out.stride = stride;
  out.count = acc.count;
  out.component_type = acc.componentType;
  return out;
}

// FLOAT VEC3 elements (positions, normals); `what` names one in messages.
std::vector<dvec3> read_vec3s(const AccessorView& view, const char* what) {
  std::vector<dvec3> values(view.count);
  for (size_t i = 0; i < view.count; ++i) {
    float xyz[3];
    std::memcpy(xyz, view.first + i * view.stride, sizeof xyz);
    values[i] = dvec3(xyz[0], xyz[1], xyz[2]);
    if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2]))
      throw InputError(view.where,
                       std::string(what) + " " + std::to_string(i) + " is not finite (NaN or Inf)");
  }
  return values;
}

// VEC2 texture coordinates: FLOAT, or normalized unsigned integers mapped to [0, 1].
std::vector<dvec2> read_texcoords(const AccessorView& view) {
  std::vector<dvec2> values(view.count);
  for (size_t i = 0; i < view.count; ++i) {
    const unsigned char* p = view.first + i * view.stride;
    for (int c = 0; c < 2; ++c) {
      double v;
      if (view.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT) {
        float f;
        std::memcpy(&f, p + 4 * c, 4);
        v = f;
      } else if (view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
        uint16_t u;
        std::memcpy(&u, p + 2 * c, 2);
        v = u / 65535.0;
      } else {
        v = p[c] / 255.0;
      }
      if (!std::isfinite(v))
        throw InputError(view.where,
                         "texture coordinate " + std::to_string(i) + " is not finite (NaN or Inf)");
      values[i][c] = v;
    }
  }
  return values;
}

// Indices (UNSIGNED_BYTE, SHORT or INT), each checked against the vertex count.
std::vector<uint32_t> read_indices(const AccessorView& view, size_t vertex_count) {
  std::vector<uint32_t> indices(view.count);
  for (size_t i = 0; i < view.count; ++i) {
    const unsigned char* p = view.first + i * view.stride;
    uint32_t value = 0;
    if (view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
      value = *p;
    } else if (view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
      uint16_t v16;
      std::memcpy(&v16, p, 2);
      value = v16;
    } else {
      std::memcpy(&value, p, 4);
    }
    if (value >= vertex_count)
      throw InputError(view.where, "index " + std::to_string(i) + " is " + std::to_string(value) +
                                       " but the primitive has " + std::to_string(vertex_count) +
                                       " vertices");
    indices[i] = value;
  }
  return indices;
}

// Triangles of a TRIANGLES / TRIANGLE_STRIP / TRIANGLE_FAN index list (glTF 2.0 §3.7.2.1),
// dropping triangles that repeat a vertex.
std::vector<u32vec3> assemble_triangles(const std::vector<uint32_t>& idx, int mode) {
  std::vector<u32vec3> triangles;
  auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
    if (a != b && b != c && a != c) triangles.emplace_back(a, b, c);
  };
  size_t n = idx.size();
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    for (size_t i = 0; i + 2 < n; i += 3) add(idx[i], idx[i + 1], idx[i + 2]);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (size_t i = 0; i + 2 < n; ++i) {
      if (i % 2 == 0)
        add(idx[i], idx[i + 1], idx[i + 2]);
      else
        add(idx[i], idx[i + 2], idx[i + 1]);
    }
  } else {
    for (size_t i = 1; i + 1 < n; ++i) add(idx[i], idx[i + 1], idx[0]);
  }
  return triangles;
}

}  // namespace dv::gltf
