// Fuzz entry: the glTF 2.0 importer, binary (.glb) when the bytes start with the glTF magic,
// else JSON (.gltf) (fuzz_entry.h).
#include <cstring>

#include "core/error.h"
#include "render/load/gltf_import.h"
#include "tests/fuzz/fuzz_entry.h"

namespace dv::fuzz {

int gltf(const uint8_t* data, size_t size) {
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  try {
    load_gltf_scene(scratch_input(data, size, binary ? ".glb" : ".gltf"));
  } catch (const InputError&) {
  }
  return 0;
}

}  // namespace dv::fuzz
