// Reusing a storage strategy's buffers across regenerations: a buffer is reallocated only when
// its size or memory changes, so repeated generation of same-size maps times the passes, not
// the allocator.
#pragma once

#include <cstdint>

#include "core/buffer.h"

namespace dv {

template <class T>
void ensure_buffer(Buffer<T>& buffer, Memory memory, int64_t count, const char* what) {
  if (buffer.size() != count || buffer.memory() != memory || (count > 0 && !buffer.data()))
    buffer = Buffer<T>(memory, count, what);
}

}  // namespace dv
