// The two executors: the CPU parallel-for covers every index once, atomics and buffers work on
// the host, and the CUDA smoke test runs the same lambda as a kernel (skipped with the reason
// where no GPU can be used); kernel timing and pass timelines.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <numeric>
#include <thread>
#include <vector>

#include "core/atomic.h"
#include "cuda/buffer.h"
#include "cuda/device_memory.h"
#include "cuda/execute.h"
#include "cuda/kernel_timing.h"
#include "cuda/pass_timer.h"

namespace dv {
namespace {

// Fills out[i] = i * i + 1 and counts visits, on the given backend.
void square_plus_one(Backend backend, int64_t n, std::vector<int64_t>& values,
                     unsigned long long& visits) {
  const Memory memory = memory_of(backend);
  Buffer<int64_t> out(memory, n, "test values");
  Buffer<unsigned long long> count(memory, 1, "test counter");
  count.fill_zero();
  const View<int64_t> o = out.view();
  unsigned long long* c = count.data();
  parallel_for(
      backend, "square_plus_one", n, DV_KERNEL_LAMBDA(int64_t i) {
        o[i] = i * i + 1;
        atomic_add(c, 1ull);
      });
  if (backend == Backend::cuda) device_synchronize("square_plus_one");
  values = out.to_vector();
  visits = count.to_vector()[0];
}

TEST(Backends, CpuParallelForVisitsEachIndexOnce) {
  const int64_t n = 100003;
  std::vector<int64_t> values;
  unsigned long long visits = 0;
  square_plus_one(Backend::cpu, n, values, visits);
  EXPECT_EQ(visits, (unsigned long long)n);
  for (int64_t i = 0; i < n; ++i) ASSERT_EQ(values[i], i * i + 1);
}

TEST(Backends, CpuParallelForRethrows) {
  EXPECT_THROW(cpu_parallel_for(1000,
                                [](int64_t i) {
                                  if (i == 517) throw Error("boom");
                                }),
               Error);
}

TEST(Backends, HostAtomicsAgreeWithSerialResults) {
  unsigned int bits = 0;
  int maximum = -1, minimum = 1 << 30;
  double sum = 0.0;
  cpu_parallel_for(
      1024,
      [&](int64_t i) {
        atomic_or(&bits, 1u << (i % 32));
        atomic_max(&maximum, int(i));
        atomic_min(&minimum, int(i) + 5);
        atomic_add(&sum, 0.5);
      },
      1);
  EXPECT_EQ(bits, 0xffffffffu);
  EXPECT_EQ(maximum, 1023);
  EXPECT_EQ(minimum, 5);
  EXPECT_DOUBLE_EQ(sum, 512.0);
  int word = 3;
  EXPECT_EQ(atomic_cas(&word, 3, 9), 3);
  EXPECT_EQ(word, 9);
  EXPECT_EQ(atomic_cas(&word, 3, 1), 9);
  EXPECT_EQ(word, 9);
}

// The value thread i adds in the combined-atomics test (a fifth add zero).
DV_HD inline unsigned long long combined_value(int64_t i) {
  return (unsigned long long)(i % 13) * (i % 5 == 0 ? 0 : 1);
}

// Totals of the warp-combined atomics on `backend` where lanes diverge: some add inside a
// branch, some after a loop of their own length, a quarter to a second counter; [2] is a
// maximum, [3] counts the threads.
std::vector<unsigned long long> combined_totals(Backend backend, int64_t n) {
  Buffer<unsigned long long> totals(memory_of(backend), 4, "test totals");
  totals.fill_zero();
  unsigned long long* t = totals.data();
  parallel_for(
      backend, "combined_atomics", n, DV_KERNEL_LAMBDA(int64_t i) {
        const unsigned long long v = combined_value(i);
        if (i % 3 == 0) {
          atomic_add_combined(t + 0, v);
        } else {
          unsigned long long spin = 0;
          for (int64_t k = 0; k < i % 7; ++k) spin += (unsigned long long)k;
          atomic_add_combined(t + (i % 4 == 1 ? 1 : 0), v + spin - spin);
        }
        atomic_max_combined(t + 2, (unsigned long long)((i * 7919) % 100003));
        atomic_add_combined(t + 3, 1ull);
      });
  if (backend == Backend::cuda) device_synchronize("combined_atomics");
  return totals.to_vector();
}

// The warp-combined atomics give the serial totals on both backends.
TEST(Backends, CombinedAtomicsEqualSerialTotalsUnderDivergence) {
  const int64_t n = (int64_t(1) << 18) + 77;
  std::vector<unsigned long long> expected(4, 0);
  for (int64_t i = 0; i < n; ++i) {
    expected[i % 3 != 0 && i % 4 == 1 ? 1 : 0] += combined_value(i);
    expected[2] = std::max(expected[2], (unsigned long long)((i * 7919) % 100003));
    expected[3] += 1;
  }
  for (Backend backend : {Backend::cpu, Backend::cuda}) {
    if (backend == Backend::cuda && !cuda_device_available()) continue;
    EXPECT_EQ(combined_totals(backend, n), expected) << to_string(backend);
  }
}

TEST(Backends, HostBufferRoundTrip) {
  std::vector<float> v(1000);
  std::iota(v.begin(), v.end(), 0.5f);
  Buffer<float> b(Memory::host, v, "host buffer");
  EXPECT_EQ(b.to_vector(), v);
  b.fill_zero();
  EXPECT_EQ(b.to_vector(), std::vector<float>(1000, 0.0f));
  EXPECT_THROW(b.upload(std::vector<float>(3)), Error);
}

TEST(Backends, CudaSmoke) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "CUDA smoke test needs a GPU: " << why;
  EXPECT_FALSE(cuda_device_name().empty());
  const int64_t n = 1 << 20;
  std::vector<int64_t> cpu_values, gpu_values;
  unsigned long long cpu_visits = 0, gpu_visits = 0;
  square_plus_one(Backend::cpu, n, cpu_values, cpu_visits);
  square_plus_one(Backend::cuda, n, gpu_values, gpu_visits);
  EXPECT_EQ(gpu_visits, (unsigned long long)n);
  EXPECT_EQ(gpu_values, cpu_values);
  std::vector<float> v(4096, 2.5f);
  Buffer<float> d(Memory::device, v, "device buffer");
  EXPECT_EQ(d.to_vector(), v);
}

// Kernel timing on: every launch is counted under its name with the block size the occupancy
// calculator chose (a multiple of the warp, at most 1024) and a positive time; off: nothing.
TEST(Backends, KernelTimingCountsLaunchesByName) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "kernel timing needs a GPU: " << why;
  std::vector<int64_t> values;
  unsigned long long visits = 0;
  reset_kernel_timings();
  set_kernel_timing(false);
  square_plus_one(Backend::cuda, 1000, values, visits);
  EXPECT_TRUE(kernel_timings().empty());
  set_kernel_timing(true);
  square_plus_one(Backend::cuda, 1 << 16, values, visits);
  square_plus_one(Backend::cuda, 1 << 16, values, visits);
  set_kernel_timing(false);
  const std::vector<KernelTiming> timings = kernel_timings();
  ASSERT_EQ(timings.size(), 1u);
  EXPECT_EQ(timings[0].name, "square_plus_one");
  EXPECT_EQ(timings[0].launches, 2);
  EXPECT_GT(timings[0].milliseconds, 0.0);
  EXPECT_EQ(timings[0].block_size % 32, 0);
  EXPECT_GE(timings[0].block_size, 32);
  EXPECT_LE(timings[0].block_size, 1024);
  EXPECT_EQ(visits, 1ull << 16);
}

// A timeline of passes: each marked pass comes back in order, named, with a positive time (a
// kernel's on CUDA); on the CPU the pass around a 3 ms sleep takes at least 3 ms.
TEST(Backends, PassTimelineTimesEachMarkedPass) {
  for (Backend backend : {Backend::cpu, Backend::cuda}) {
    std::string why;
    if (backend == Backend::cuda && !cuda_device_available(&why)) continue;
    std::vector<int64_t> values;
    unsigned long long visits = 0;
    PassTimeline timeline(backend);
    square_plus_one(backend, 1 << 16, values, visits);
    timeline.mark("first");
    if (backend == Backend::cpu) std::this_thread::sleep_for(std::chrono::milliseconds(3));
    square_plus_one(backend, 1 << 16, values, visits);
    timeline.mark("second");
    const auto passes = timeline.finish();
    ASSERT_EQ(passes.size(), 2u) << to_string(backend);
    EXPECT_EQ(passes[0].first, "first");
    EXPECT_EQ(passes[1].first, "second");
    EXPECT_GT(passes[0].second, 0.0) << to_string(backend);
    EXPECT_GT(passes[1].second, 0.0) << to_string(backend);
    if (backend == Backend::cpu) EXPECT_GE(passes[1].second, 3.0);
  }
}

TEST(Backends, BackendNamesAndAvailability) {
  EXPECT_EQ(parse_backend("cpu"), Backend::cpu);
  EXPECT_EQ(parse_backend("cuda"), Backend::cuda);
  EXPECT_THROW(parse_backend("opencl"), InputError);
  EXPECT_NO_THROW(require_backend(Backend::cpu));
  if (!cuda_device_available()) {
    EXPECT_THROW(require_backend(Backend::cuda), Error);
    EXPECT_EQ(default_backend(), Backend::cpu);
  }
}

}  // namespace
}  // namespace dv
