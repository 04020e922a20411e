// Stable sort of values by key, largest key first, on either backend (CUB's radix sort on CUDA,
// std::stable_sort on the host): orders work heaviest first, so that the items that take longest
// start before the lighter ones (the camera pass's volume tiles, render/frame/fragment_lanes.h).
#pragma once

#include <cstdint>

#include "cuda/buffer.h"
#include "cuda/execute.h"

namespace dv {

// sorted_values receives `values` ordered by decreasing key, equal keys in their input order.
// Keys below 2^key_bits only (the radix sort looks at those bits). On CUDA it is queued on the
// default stream with scratch from the stream-ordered allocator: no host round trip. All views
// live in the memory of `backend` and have the same size.
void sort_by_key_descending_queued(Backend backend, View<const uint32_t> keys,
                                   View<const int32_t> values, View<int32_t> sorted_values,
                                   int key_bits);

}  // namespace dv
