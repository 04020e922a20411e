// Exclusive prefix sum in place over a buffer on either backend (CUB on CUDA, std::exclusive_scan
// on the host): the step between counting and packing of every exact-size structure (the
// compact DSM storage, tile lists, the voxelizers' work items).
#pragma once

#include <cstdint>

#include "core/hd.h"
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

// The owner of work item `item` in a scan's output: the last index i in [0, count) with
// starts[i] <= item, for non-decreasing `starts` whose first value is <= item (owners without
// items share their start with the next one; of equal starts the last is taken). One binary
// search per kernel thread, CPU and CUDA alike.
template <class T>
DV_HD int64_t owner_of_item(View<const T> starts, int64_t count, int64_t item) {
  int64_t lo = 0, hi = count - 1;
  while (lo < hi) {
    const int64_t mid = (lo + hi + 1) / 2;
    if (int64_t(starts[mid]) <= item)
      lo = mid;
    else
      hi = mid - 1;
  }
  return lo;
}

}  // namespace dv
