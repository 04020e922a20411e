// Refusing a reservation the machine cannot hold before asking for it, with a message that
// names the structure and the bytes ("dsm texture3d atlas: 16.5 GB asked, 7.9 GB free on the
// host"), instead of an allocator failure (or, on the host, overcommitted pages that fail
// later). DEEPVOX_MEMORY_LIMIT (bytes) caps what counts as free, which is how tests provoke it.
#pragma once

#include <cstdint>
#include <string>

#include "core/error.h"
#include "cuda/buffer.h"

namespace dv {

// Memory that could not be had: a reservation beyond the free memory (check_reservation) or a
// failed device allocation (device_allocate). Carries the bytes asked for, so the suite runner
// records them in the experiment's failed row and goes on with the next experiment.
class OutOfMemory : public InputError {
 public:
  OutOfMemory(const std::string& what, const std::string& problem, int64_t bytes)
      : InputError(what, problem), bytes_(bytes) {}
  int64_t bytes() const { return bytes_; }

 private:
  int64_t bytes_;
};

// Free bytes of `memory` now (MemAvailable on the host, the device's free memory on the GPU),
// at most DEEPVOX_MEMORY_LIMIT when that is set.
int64_t free_memory_bytes(Memory memory);
// Throws OutOfMemory(what, ...) when `bytes` exceed free_memory_bytes(memory).
void check_reservation(Memory memory, int64_t bytes, const std::string& what);
// "16.5 GB" (decimal units, 3 significant digits).
std::string format_bytes(int64_t bytes);

}  // namespace dv
