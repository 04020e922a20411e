// Raw volume reading and writing (see volume_io.h). Bytes are assembled explicitly in the
// file's byte order, so the result does not depend on the host's endianness.
#include "render/io/volume_io.h"

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <vector>

#include "core/error.h"

namespace dv {

namespace {

std::string dims_text(ivec3 dims) {
  return std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" + std::to_string(dims.z);
}

// Unsigned value of `count` bytes starting at `p`, in the given byte order.
uint32_t read_unsigned(const unsigned char* p, int count, bool big_endian) {
  uint32_t value = 0;
  for (int b = 0; b < count; ++b) {
    const uint32_t byte = big_endian ? p[b] : p[count - 1 - b];
    value = (value << 8) | byte;
  }
  return value;
}

std::vector<unsigned char> read_exact_file(const std::string& path, uint64_t expected_bytes,
                                           ivec3 dims, RawType type) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw InputError(path, "volume file not found");
  if (!fs::is_regular_file(status)) throw InputError(path, "volume path is not a regular file");
  const uintmax_t actual_bytes = fs::file_size(path, ec);
  if (ec) throw InputError(path, "cannot read the file size: " + ec.message());
  if (actual_bytes != expected_bytes) {
    throw InputError(path, "file size is " + std::to_string(actual_bytes) + " bytes, expected " +
                               std::to_string(expected_bytes) + " bytes (" + dims_text(dims) +
                               " samples of " + to_string(type) + ")");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open file");
  std::vector<unsigned char> bytes(expected_bytes);
  in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
  if (uint64_t(in.gcount()) != expected_bytes) {
    throw InputError(path, "file ended after " + std::to_string(in.gcount()) + " bytes, expected " +
                               std::to_string(expected_bytes));
  }
  return bytes;
}

}  // namespace

RawType parse_raw_type(const std::string& text, const std::string& where) {
  if (text == "uint8") return RawType::uint8;
  if (text == "uint16") return RawType::uint16;
  if (text == "float32") return RawType::float32;
  throw InputError(where, "unknown raw type '" + text + "' (known: uint8, uint16, float32)");
}

const char* to_string(RawType type) {
  switch (type) {
    case RawType::uint8:
      return "uint8";
    case RawType::uint16:
      return "uint16";
    case RawType::float32:
      return "float32";
  }
  return "unknown";
}

int raw_type_size(RawType type) {
  switch (type) {
    case RawType::uint8:
      return 1;
    case RawType::uint16:
      return 2;
    case RawType::float32:
      return 4;
  }
  return 0;
}

void check_volume_dims(ivec3 dims, const std::string& where) {
  if (dims.x <= 0 || dims.y <= 0 || dims.z <= 0) {
    throw InputError(where, "zero-size volume: dims " + dims_text(dims) + " must all be >= 1");
  }
  const int64_t voxels = int64_t(dims.x) * dims.y * dims.z;
  if (voxels > kMaxVolumeVoxels) {
    throw InputError(where, "volume too large: dims " + dims_text(dims) + " give " +
                                std::to_string(voxels) + " samples, at most " +
                                std::to_string(kMaxVolumeVoxels) + " are allowed");
  }
}

VolumeGrid load_raw_volume(const std::string& path, ivec3 dims, RawType type, dvec3 spacing,
                           bool big_endian) {
  check_volume_dims(dims, path);
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(spacing[a]) || spacing[a] <= 0.0) {
      throw InputError(path, "volume spacing must be positive and finite");
    }
  }
  const int element = raw_type_size(type);
  const int64_t voxels = int64_t(dims.x) * dims.y * dims.z;
  const std::vector<unsigned char> bytes =
      read_exact_file(path, uint64_t(voxels) * uint64_t(element), dims, type);

  VolumeGrid volume;
  volume.name = path;
  volume.dims = dims;
  volume.spacing = spacing;
  volume.origin = -0.5 * dvec3(dims - 1) * spacing;
  volume.density.resize(size_t(voxels));
  for (int64_t i = 0; i < voxels; ++i) {
    const uint32_t bits = read_unsigned(bytes.data() + i * element, element, big_endian);
    switch (type) {
      case RawType::uint8:
        volume.density[size_t(i)] = float(bits) / 255.0f;
        break;
      case RawType::uint16:
        volume.density[size_t(i)] = float(bits) / 65535.0f;
        break;
      case RawType::float32: {
        const float value = std::bit_cast<float>(bits);
        if (!std::isfinite(value)) {
          const int64_t x = i % dims.x;
          const int64_t y = (i / dims.x) % dims.y;
          const int64_t z = i / (int64_t(dims.x) * dims.y);
          throw InputError(path, "sample (" + std::to_string(x) + ", " + std::to_string(y) + ", " +
                                     std::to_string(z) + ") is not a finite number");
        }
        volume.density[size_t(i)] = value;
        break;
      }
    }
  }
  return volume;
}

void save_raw_volume(const std::string& path, const VolumeGrid& volume) {
  if (volume.dims.x <= 0 || volume.dims.y <= 0 || volume.dims.z <= 0 ||
      int64_t(volume.density.size()) != volume.voxel_count()) {
    throw InputError(path, "cannot save volume '" + volume.name +
                               "': " + std::to_string(volume.density.size()) +
                               " densities for dims " + dims_text(volume.dims));
  }
  std::vector<unsigned char> bytes(volume.density.size() * 4);
  for (size_t i = 0; i < volume.density.size(); ++i) {
    const uint32_t bits = std::bit_cast<uint32_t>(volume.density[i]);
    for (int b = 0; b < 4; ++b) bytes[i * 4 + size_t(b)] = (unsigned char)(bits >> (8 * b));
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw InputError(path, "cannot create file");
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  if (!out) throw InputError(path, "write failed");
}

}  // namespace dv
