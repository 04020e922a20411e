// Reusing a storage strategy's buffers across regenerations: a buffer is reallocated only when
// its size or memory changes, so repeated generation of same-size maps times the passes, not
// the allocator. A new reservation larger than the free memory is refused first with a message
// naming the structure and the bytes (cuda/memory_check.h).
#pragma once

#include <cstdint>

#include "cuda/buffer.h"
#include "cuda/memory_check.h"

namespace dv {

template <class T>
void ensure_buffer(Buffer<T>& buffer, Memory memory, int64_t count, const char* what) {
  if (buffer.size() != count || buffer.memory() != memory || (count > 0 && !buffer.data())) {
    buffer = Buffer<T>();
    check_reservation(memory, count * int64_t(sizeof(T)), what);
    buffer = Buffer<T>(memory, count, what);
  }
}

}  // namespace dv
