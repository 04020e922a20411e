// Fuzz entry: the mesh readers; the first byte picks the format (OBJ, OFF, PLY, STL by its
// value modulo 4), the rest is the file (fuzz_entry.h).
#include "core/error.h"
#include "render/io/mesh_io.h"
#include "tests/fuzz/fuzz_entry.h"

namespace dv::fuzz {

int mesh(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  static const char* const kExtensions[] = {".obj", ".off", ".ply", ".stl"};
  try {
    load_mesh_file(scratch_input(data + 1, size - 1, kExtensions[data[0] % 4]));
  } catch (const InputError&) {
  }
  return 0;
}

}  // namespace dv::fuzz
