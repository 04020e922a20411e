// Variable amounts of work per primitive as one flat range of work items, shared by the
// voxelizers that split their work (sat: columns per large triangle; atlas-compute: texels per
// triangle): per-primitive counts become offsets (on the host with work_item_offsets, where
// they live with exclusive_scan_queued from cuda/scan.h, or appended by a kernel to a
// PackedWorkList with no scan at all), and a kernel thread finds the primitive that owns its
// item by binary search over them (owner_of_item, cuda/scan.h; CPU and CUDA alike).
#pragma once

#include <bit>
#include <cstdint>
#include <vector>

#include "core/atomic.h"
#include "core/hd.h"
#include "cuda/buffer.h"
#include "cuda/scan.h"

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

// Primitives appended from a kernel with their item counts, offsets included, no scan and no
// host round trip: one 64-bit counter holds the entries in its high bits and their items in
// its low `item_bits`, so an append takes its entry index and its first item from the same
// atomic add; first items therefore increase with the entry index (owner_of_item finds an
// item's entry) whatever order the threads append in. The host sizes item_bits and the number
// of primitives per list with packed_work_list_batch so that neither part can overflow.
struct PackedWorkList {
  unsigned long long* counter = nullptr;  // zero before the appending kernel
  int64_t* primitive = nullptr;           // entry -> primitive
  int64_t* first = nullptr;               // entry -> its first item
  int item_bits = 32;

  DV_HD void append(int64_t id, int64_t items) const {
    const unsigned long long old =
        atomic_add(counter, (1ull << item_bits) + static_cast<unsigned long long>(items));
    const int64_t entry = int64_t(old >> item_bits);
    primitive[entry] = id;
    first[entry] = int64_t(old & ((1ull << item_bits) - 1ull));
  }
  // Read by a later kernel (or the host) once the appending kernel finished.
  DV_HD int64_t entries() const { return int64_t(*counter >> item_bits); }
  DV_HD int64_t items() const { return int64_t(*counter & ((1ull << item_bits) - 1ull)); }
  DV_HD View<const int64_t> firsts() const { return {first, entries()}; }
};

// Item bits of a list of at most `entries` entries: what the entry count leaves of 64 bits.
inline int packed_item_bits(int64_t entries) {
  return 64 - int(std::bit_width(static_cast<uint64_t>(entries)));
}

// The most primitives (at most `primitives`, at least 1) one PackedWorkList may take when each
// brings at most `max_items` items, so that entries and items both fit: batch * max_items <
// 2^packed_item_bits(batch).
inline int64_t packed_work_list_batch(int64_t primitives, int64_t max_items) {
  int64_t batch = primitives < 1 ? 1 : primitives;
  const auto fits = [max_items](int64_t n) {
    const uint64_t item_limit = (uint64_t(1) << packed_item_bits(n)) - 1u;
    return max_items <= 0 || uint64_t(n) <= item_limit / uint64_t(max_items);
  };
  while (batch > 1 && !fits(batch)) batch = (batch + 1) / 2;
  return batch;
}

}  // namespace dv
