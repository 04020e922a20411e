// Fuzz entry: the deepvox JSON scene loader (fuzz_entry.h).
#include "core/error.h"
#include "render/load/scene_loader.h"
#include "tests/fuzz/fuzz_entry.h"

namespace dv::fuzz {

int scene_json(const uint8_t* data, size_t size) {
  try {
    load_scene(scratch_input(data, size, ".json"));
  } catch (const InputError&) {
  }
  return 0;
}

}  // namespace dv::fuzz
