// Raw density volume files: headerless arrays of uint8, uint16 or float32 samples (x fastest,
// then y, then z), the format CT and simulation volumes are commonly shipped in. Loading checks
// the file size against the dims exactly, since a raw file carries no header to catch a wrong
// guess. Saving writes float32 little endian (handy for tests and exports).
#pragma once

#include <cstdint>
#include <string>

#include "core/math.h"
#include "engine/scene/scene.h"

namespace dv {

enum class RawType : uint8_t { uint8, uint16, float32 };

// "uint8" | "uint16" | "float32"; anything else throws InputError(where, ...) listing them.
RawType parse_raw_type(const std::string& text, const std::string& where);
const char* to_string(RawType type);
int raw_type_size(RawType type);  // bytes per sample

// Most samples a volume may have (2^31, 8 GiB of floats): guards allocations against typos.
inline constexpr int64_t kMaxVolumeVoxels = int64_t(1) << 31;

// Throws InputError(where, ...) unless every dim is >= 1 ("zero-size volume") and the voxel
// count is at most kMaxVolumeVoxels.
void check_volume_dims(ivec3 dims, const std::string& where);

// Reads a raw volume. Integer samples are normalised by their type's maximum (255, 65535);
// float32 samples are kept as they are but must be finite. The file size must equal
// dims.x * dims.y * dims.z * sample size exactly. spacing must be positive; the grid is
// centred on the origin (origin = -0.5 * (dims - 1) * spacing). The result's name is the path.
// Every error is an InputError naming the file.
VolumeGrid load_raw_volume(const std::string& path, ivec3 dims, RawType type, dvec3 spacing,
                           bool big_endian = false);

// Writes the densities as float32 little endian (dims and placement are not stored).
void save_raw_volume(const std::string& path, const VolumeGrid& volume);

}  // namespace dv
