// Variable amounts of work per primitive as one flat range of work items, shared by the
// voxelizers that split their work (sat: columns per triangle; atlas-compute: texels per
// triangle): per-primitive counts become offsets (on the host with work_item_offsets, where
// they live with exclusive_scan_queued from cuda/scan.h), and a kernel thread finds the
// primitive that owns its item by binary search over them (CPU and CUDA alike).
#pragma once

#include <cstdint>
#include <vector>

#include "core/hd.h"
#include "cuda/buffer.h"

namespace dv {

// Exclusive prefix sums of `counts` plus the total as the last element (counts.size() + 1
// values): primitive i owns items [offsets[i], offsets[i + 1]).
inline std::vector<int64_t> work_item_offsets(const std::vector<int64_t>& counts) {
  std::vector<int64_t> offsets(counts.size() + 1);
  int64_t total = 0;
  for (size_t i = 0; i < counts.size(); ++i) {
    offsets[i] = total;
    total += counts[i];
  }
  offsets[counts.size()] = total;
  return offsets;
}

// The last of the `primitives` first entries of `first` that is <= item: the primitive owning
// `item` (primitives without items share their offset with the next one and are skipped).
DV_HD inline int64_t work_item_owner(const View<const int64_t>& first, int64_t primitives,
                                     int64_t item) {
  int64_t lo = 0, hi = primitives - 1;
  while (lo < hi) {
    const int64_t mid = (lo + hi + 1) / 2;
    if (first[mid] <= item)
      lo = mid;
    else
      hi = mid - 1;
  }
  return lo;
}

}  // namespace dv
