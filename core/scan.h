// Exclusive prefix sum in place over a buffer on either backend (CUB through Thrust on CUDA,
// std::exclusive_scan on the host): the step between counting and packing of every
// exact-size structure (the compact DSM storage, tile lists).
#pragma once

#include <cstdint>

#include "core/buffer.h"
#include "core/execute.h"

namespace dv {

// values[i] becomes the sum of values[0 .. i-1]; returns the sum of all of them. `values` lives
// in the memory of `backend`.
int64_t exclusive_scan_in_place(Backend backend, View<int64_t> values);

}  // namespace dv
