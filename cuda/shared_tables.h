// Read-only tables that every thread of a kernel reads again and again (a frame's lights, its
// shadow maps' light and face headers), copied into each block's shared memory before the
// kernel's body runs (parallel_for_with_tables, cuda/execute_with_tables.h), so that a thread's
// reads of them wait on shared memory instead of the cache hierarchy. Tables are placed in the
// order they were added, each that fits the block's budget; the others are read where they are.
// On the CPU nothing is copied.
#pragma once

#include <cstdint>

#include "core/hd.h"

namespace dv {

struct SharedTables {
  static constexpr int kMaxTables = 4;
  const void* source[kMaxTables] = {};
  int64_t bytes[kMaxTables] = {};
  int32_t offset[kMaxTables] = {-1, -1, -1, -1};  // placed: bytes into a block's copy; -1: not
  int count = 0;
  int32_t placed_bytes = 0;  // shared memory a block needs for the placed tables

  // Adds the table a view (a data pointer and an element count) reads; returns its index, that
  // of an earlier table with the same data, or -1 when it is empty or kMaxTables are taken.
  template <class V>
  int add(const V& v) {
    if (v.size <= 0 || v.data == nullptr) return -1;
    for (int k = 0; k < count; ++k)
      if (source[k] == v.data) return k;
    if (count == kMaxTables) return -1;
    source[count] = v.data;
    bytes[count] = v.size * int64_t(sizeof(*v.data));
    return count++;
  }

  // Places the tables in order, each that fits `budget` bytes with the ones placed before it
  // (offsets aligned to 16 bytes); a table whose size is not a whole number of 4-byte words
  // stays where it is.
  void place(int64_t budget) {
    int64_t end = 0;
    for (int k = 0; k < count; ++k) {
      offset[k] = -1;
      const int64_t at = (end + 15) / 16 * 16;
      if (bytes[k] % 4 != 0 || at + bytes[k] > budget) continue;
      offset[k] = int32_t(at);
      end = at + bytes[k];
    }
    placed_bytes = int32_t(end);
  }

  // Where table k lies in a block's copy, -1 when it is not there (or k is no table).
  int32_t placed_offset(int k) const { return k < 0 ? -1 : offset[k]; }

  // Every thread of a block copies its share of the placed tables' words into `copy` (the
  // caller synchronises the block after). The tables' indices are constants, so that a kernel
  // reads this struct from its parameters instead of a copy in local memory.
  DV_HD void copy_into(unsigned char* copy, int thread, int threads) const {
#pragma unroll
    for (int k = 0; k < kMaxTables; ++k) {
      if (k >= count || offset[k] < 0) continue;
      const auto* from = static_cast<const uint32_t*>(source[k]);
      auto* to = reinterpret_cast<uint32_t*>(copy + offset[k]);
      for (int64_t w = thread; w < bytes[k] / 4; w += threads) to[w] = from[w];
    }
  }
};

// The view `original` reading a block's copy `copy` of its table at `offset` (from
// placed_offset), or where it is when there is no copy (null, as on the CPU) or it was not placed.
template <class V>
DV_HD V placed_view(V original, int32_t offset, const unsigned char* copy) {
  if (copy == nullptr || offset < 0) return original;
  original.data = reinterpret_cast<decltype(original.data)>(copy + offset);
  return original;
}

}  // namespace dv
