// Refusing a reservation the machine cannot hold before asking for it, with a message that
// names the structure and the bytes ("dsm texture3d atlas: 16.5 GB asked, 7.9 GB free on the
// host"), instead of an allocator failure (or, on the host, overcommitted pages that fail
// later). DEEPVOX_MEMORY_LIMIT (bytes) caps what counts as free, which is how tests provoke it.
#pragma once

#include <cstdint>
#include <string>

#include "cuda/buffer.h"

namespace dv {

// Free bytes of `memory` now (MemAvailable on the host, the device's free memory on the GPU),
// at most DEEPVOX_MEMORY_LIMIT when that is set.
int64_t free_memory_bytes(Memory memory);
// Throws InputError(what, ...) when `bytes` exceed free_memory_bytes(memory).
void check_reservation(Memory memory, int64_t bytes, const std::string& what);
// "16.5 GB" (decimal units, 3 significant digits).
std::string format_bytes(int64_t bytes);

}  // namespace dv
