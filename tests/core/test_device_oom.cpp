// A real out-of-memory on the device, provoked through the code paths (CUDA only; skipped
// without a GPU): the card filled with ballast buffers until an allocation fails, then the
// scratch of the radix sort and of the scan, and a buffer, each fail with OutOfMemory naming
// the structure and the bytes asked (what a suite records as the row `out_of_memory`); with the
// ballast given back the same sort and scan run and equal the host's, and the device can hand
// out again what it could before.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "cuda/buffer.h"
#include "cuda/device_memory.h"
#include "cuda/memory_check.h"
#include "cuda/scan.h"
#include "cuda/sort.h"

namespace dv {
namespace {

// Device buffers taken until the card has nothing left: pieces of 1 GB, then smaller down to
// 1 kB, each size until its allocation fails (which must be OutOfMemory with its bytes).
std::vector<Buffer<char>> fill_the_device() {
  std::vector<Buffer<char>> ballast;
  for (int64_t piece : {int64_t(1) << 30, int64_t(64) << 20, int64_t(2) << 20, int64_t(64) << 10,
                        int64_t(1) << 10}) {
    for (;;) {
      try {
        ballast.emplace_back(Memory::device, piece, "ballast");
      } catch (const OutOfMemory& e) {
        EXPECT_EQ(e.bytes(), piece);
        EXPECT_NE(std::string(e.what()).find("ballast: "), std::string::npos) << e.what();
        break;
      }
    }
  }
  return ballast;
}

TEST(DeviceOutOfMemory, SortScanAndBuffersFailWithTheBytesAndRunAgainOnceFreed) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "needs a GPU: " << why;
  const int64_t free_before = int64_t(device_free_bytes());
  constexpr int64_t n = int64_t(1) << 22;
  std::mt19937 random(7);
  std::vector<uint32_t> keys(n);
  std::vector<int32_t> values(n);
  std::vector<int64_t> counts(n);
  for (int64_t i = 0; i < n; ++i) {
    keys[size_t(i)] = random() & 0xffffu;
    values[size_t(i)] = int32_t(i);
    counts[size_t(i)] = int64_t(random() % 100);
  }
  const Buffer<uint32_t> d_keys(Memory::device, std::span<const uint32_t>(keys));
  const Buffer<int32_t> d_values(Memory::device, std::span<const int32_t>(values));
  Buffer<int32_t> d_sorted(Memory::device, n);
  Buffer<int64_t> d_counts(Memory::device, std::span<const int64_t>(counts));
  device_synchronize("upload");
  {
    std::vector<Buffer<char>> ballast = fill_the_device();
    ASSERT_FALSE(ballast.empty());
    try {
      sort_by_key_descending_queued(Backend::cuda, d_keys.const_view(), d_values.const_view(),
                                    d_sorted.view(), 16);
      ADD_FAILURE() << "the sort found scratch on a full device";
    } catch (const OutOfMemory& e) {
      EXPECT_GE(e.bytes(), n * int64_t(sizeof(uint32_t)));  // the sorted keys at least
      EXPECT_NE(std::string(e.what()).find("sort_by_key_descending scratch: "), std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find(std::to_string(e.bytes()) + " bytes) asked"),
                std::string::npos)
          << e.what();
    }
    try {
      exclusive_scan_queued(Backend::cuda, d_counts.view());
      ADD_FAILURE() << "the scan found scratch on a full device";
    } catch (const OutOfMemory& e) {
      EXPECT_GT(e.bytes(), 0);
      EXPECT_NE(std::string(e.what()).find("exclusive_scan scratch: "), std::string::npos)
          << e.what();
    }
    std::printf("device full: %zu ballast buffers; sort and scan refused with OutOfMemory\n",
                ballast.size());
  }
  // The ballast given back: both run, and equal the host's.
  sort_by_key_descending_queued(Backend::cuda, d_keys.const_view(), d_values.const_view(),
                                d_sorted.view(), 16);
  std::vector<int32_t> want(values);
  std::stable_sort(want.begin(), want.end(),
                   [&](int32_t a, int32_t b) { return keys[size_t(a)] > keys[size_t(b)]; });
  EXPECT_EQ(d_sorted.to_vector(), want);
  const int64_t total = exclusive_scan_in_place(Backend::cuda, d_counts.view());
  std::vector<int64_t> sums(counts.size());
  std::exclusive_scan(counts.begin(), counts.end(), sums.begin(), int64_t(0));
  EXPECT_EQ(d_counts.to_vector(), sums);
  EXPECT_EQ(total, std::accumulate(counts.begin(), counts.end(), int64_t(0)));
  device_synchronize("sort and scan after the ballast");
  // The pool keeps what was freed and counts it as free: what the device can hand out is what
  // it could before, less the inputs, within 64 MB of other processes on a shared card.
  const int64_t inputs =
      int64_t(d_keys.bytes() + d_values.bytes() + d_sorted.bytes() + d_counts.bytes());
  EXPECT_GT(int64_t(device_free_bytes()), free_before - inputs - (int64_t(64) << 20));
}

// DEEPVOX_MEMORY_LIMIT caps every device allocation (not only the storages' reservations): the
// sort's scratch beyond it is refused the same way.
TEST(DeviceOutOfMemory, MemoryLimitCapsTheScratchToo) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "needs a GPU: " << why;
  constexpr int64_t n = int64_t(1) << 20;
  const Buffer<uint32_t> keys(Memory::device, n);
  const Buffer<int32_t> values(Memory::device, n);
  Buffer<int32_t> sorted(Memory::device, n);
  setenv("DEEPVOX_MEMORY_LIMIT", "1000000", 1);  // 1 MB: less than the 4 MB of sorted keys
  try {
    sort_by_key_descending_queued(Backend::cuda, keys.const_view(), values.const_view(),
                                  sorted.view(), 16);
    ADD_FAILURE() << "the scratch ignored DEEPVOX_MEMORY_LIMIT";
  } catch (const OutOfMemory& e) {
    EXPECT_GE(e.bytes(), n * int64_t(sizeof(uint32_t)));
    EXPECT_NE(std::string(e.what()).find("sort_by_key_descending scratch"), std::string::npos)
        << e.what();
  }
  unsetenv("DEEPVOX_MEMORY_LIMIT");
}

}  // namespace
}  // namespace dv
