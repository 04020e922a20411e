// Exclusive prefix sum in place over a buffer on either backend (CUB on CUDA, std::exclusive_scan
// on the host): the step between counting and packing of every exact-size structure (the
// compact DSM storage, tile lists, the voxelizers' work items).
#pragma once

#include <cstdint>

#include "cuda/buffer.h"
#include "cuda/execute.h"

namespace dv {

// values[i] becomes the sum of values[0 .. i-1]; returns the sum of all of them. `values` lives
// in the memory of `backend`.
int64_t exclusive_scan_in_place(Backend backend, View<int64_t> values);

// The same scan without the total and without waiting for it: on CUDA it is queued on the
// default stream (scratch from the stream-ordered allocator), so a kernel launched next reads
// the sums with no host round trip. A zero appended to the values leaves the total in the last.
void exclusive_scan_queued(Backend backend, View<int64_t> values);

}  // namespace dv
