// Read-only tables copied into each CUDA block's shared memory (cuda/shared_tables.h,
// parallel_for_with_tables): which tables a budget places and where, and that a kernel reads the
// same values through the block's copy (checked to be in shared memory) as the CPU reads where
// the tables are, a table past the budget staying in global memory.
#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#include "cuda/buffer.h"
#include "cuda/device_memory.h"
#include "cuda/execute_with_tables.h"
#include "cuda/shared_tables.h"

namespace dv {
namespace {

template <class T>
View<const T> view_of(const std::vector<T>& v) {
  return {v.data(), int64_t(v.size())};
}

TEST(SharedTables, PlacesInOrderEachTableThatFitsTheBudget) {
  const std::vector<int32_t> small(10), big(1000), last(3);
  const std::vector<uint16_t> odd(3);  // 6 bytes: not whole 4-byte words
  SharedTables tables;
  EXPECT_EQ(tables.add(view_of(small)), 0);
  EXPECT_EQ(tables.add(view_of(big)), 1);
  EXPECT_EQ(tables.add(view_of(small)), 0) << "the same data is one table";
  EXPECT_EQ(tables.add(View<const int32_t>{}), -1) << "an empty view is no table";
  EXPECT_EQ(tables.add(view_of(odd)), 2);
  EXPECT_EQ(tables.add(view_of(last)), 3);
  EXPECT_EQ(tables.add(view_of(std::vector<int32_t>(5))), -1) << "past kMaxTables";

  tables.place(1000);  // small at 0 (40 bytes); big (4000) does not fit; odd stays; last at 48
  EXPECT_EQ(tables.offset[0], 0);
  EXPECT_EQ(tables.offset[1], -1);
  EXPECT_EQ(tables.offset[2], -1);
  EXPECT_EQ(tables.offset[3], 48);
  EXPECT_EQ(tables.placed_bytes, 60);

  tables.place(8000);
  EXPECT_EQ(tables.offset[1], 48);
  EXPECT_EQ(tables.offset[3], 4048);
  EXPECT_EQ(tables.placed_bytes, 4060);

  EXPECT_EQ(tables.placed_offset(3), 4048);
  EXPECT_EQ(tables.placed_offset(-1), -1) << "no table";

  // Without a block's copy (host code, CPU runs) every view reads where its table is.
  EXPECT_EQ(placed_view(view_of(small), tables.placed_offset(0), nullptr).data, small.data());
  alignas(16) unsigned char copy[8192];
  const auto in_copy = [&](const void* p) { return static_cast<const unsigned char*>(p) - copy; };
  EXPECT_EQ(in_copy(placed_view(view_of(small), tables.placed_offset(0), copy).data), 0);
  EXPECT_EQ(in_copy(placed_view(view_of(last), tables.placed_offset(3), copy).data), 4048);
  EXPECT_EQ(placed_view(view_of(last), tables.placed_offset(3), copy).size, 3);
  EXPECT_EQ(placed_view(view_of(odd), tables.placed_offset(2), copy).data, odd.data())
      << "not placed";
}

// out[i] = a[i % a.size] + b[i % b.size]; in_shared[i] = 2 * (a read from shared memory) + (b
// read from shared memory), in device code, 0 on the CPU.
void sum_tables(Backend backend, const std::vector<int32_t>& a, const std::vector<int32_t>& b,
                std::vector<int32_t>& out, std::vector<int32_t>& in_shared) {
  const Memory memory = memory_of(backend);
  Buffer<int32_t> a_buffer(memory, std::span<const int32_t>(a), "table a");
  Buffer<int32_t> b_buffer(memory, std::span<const int32_t>(b), "table b");
  const int64_t n = 5000;
  Buffer<int32_t> sums(memory, n, "sums"), where(memory, n, "where");
  SharedTables tables;
  const View<const int32_t> av = a_buffer.const_view(), bv = b_buffer.const_view();
  const int ka = tables.add(av), kb = tables.add(bv);
  tables.place(shared_table_budget<2>(backend));
  const int32_t a_at = tables.placed_offset(ka), b_at = tables.placed_offset(kb);
  const View<int32_t> s = sums.view(), w = where.view();
  parallel_for_with_tables<2>(
      backend, "sum_tables", n, tables, DV_KERNEL_LAMBDA(int64_t i, const unsigned char* copy) {
        const View<const int32_t> ta = placed_view(av, a_at, copy),
                                  tb = placed_view(bv, b_at, copy);
        s[i] = ta[i % ta.size] + tb[i % tb.size];
        int shared = 0;
#if defined(__CUDA_ARCH__)
        shared = 2 * int(__isShared(ta.data)) + int(__isShared(tb.data));
#endif
        w[i] = shared;
      });
  if (backend == Backend::cuda) device_synchronize("sum_tables");
  out = sums.to_vector();
  in_shared = where.to_vector();
}

void expect_sums(Backend backend, int expected_in_shared) {
  std::vector<int32_t> a(300), b(40000);  // b: 160,000 bytes, past any block's budget
  std::iota(a.begin(), a.end(), 7);
  std::iota(b.begin(), b.end(), -20000);
  std::vector<int32_t> out, in_shared;
  sum_tables(backend, a, b, out, in_shared);
  for (size_t i = 0; i < out.size(); ++i) {
    ASSERT_EQ(out[i], a[i % a.size()] + b[i % b.size()]) << "thread " << i;
    ASSERT_EQ(in_shared[i], expected_in_shared) << "thread " << i;
  }
}

TEST(SharedTables, CpuReadsTheTablesWhereTheyAre) {
  expect_sums(Backend::cpu, 0);
}

TEST(SharedTables, CudaReadsThePlacedTableFromSharedMemory) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "needs a GPU: " << why;
  expect_sums(Backend::cuda, 2);  // a from shared memory, b from global
}

}  // namespace
}  // namespace dv
