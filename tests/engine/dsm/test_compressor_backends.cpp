// The compressor as device code: synthetic texel walks (float-only arithmetic, so both sides
// round alike) compressed inside parallel_for on the CPU, checked against the bound, and on
// CUDA, which must give the same nodes bit for bit (skipped with the reason without a GPU).
// nvcc compiles this file when CUDA is on (deepvox_kernel_sources in CMakeLists.txt).
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "compressor_test_support.h"
#include "cuda/buffer.h"
#include "cuda/device_memory.h"
#include "cuda/execute.h"

namespace dv::test {
namespace {

constexpr int kTexels = 4096;
constexpr int kCapacity = 48;  // small enough that texels overflow at small eps
constexpr int kSteps = 160;

DV_HD inline uint32_t mix(uint32_t x) {
  x ^= x >> 16, x *= 0x7feb352du, x ^= x >> 15, x *= 0x846ca68bu, x ^= x >> 16;
  return x;
}

// One texel's walk: media of varying density with surface crossings, from texel's own hash.
template <class Consumer>
DV_HD void synthetic_walk(uint32_t texel, Consumer& out) {
  float z = 1.0f + float(mix(texel) & 1023u) / 64.0f, t = 1.0f;
  const float density = float(mix(texel + 77u) & 255u) / 8192.0f;
  out.push(z, t);
  for (int k = 0; k < kSteps; ++k) {
    const uint32_t h = mix(texel * 2654435761u + uint32_t(k));
    z += float((h >> 8) & 63u) / 256.0f;  // zero-length gaps included
    if ((h & 31u) == 0u) {
      const float after = t * (float((h >> 16) & 255u) / 256.0f);
      out.push_step(z, t, after);
      t = after;
    } else {
      t *= 1.0f - density * float((h >> 16) & 255u) / 256.0f;
      out.push(z, t);
    }
  }
}

struct Recorder {
  Samples* samples;
  void push(float z, float v) { samples->push_back({z, v}); }
  void push_step(float z, float before, float after) { push(z, before), push(z, after); }
};

struct CompressedWalks {
  std::vector<float> z, v;
  std::vector<int> nodes, stored, overflow;
  std::vector<float> error;
};

CompressedWalks compress_walks(Backend backend, float eps) {
  const Memory memory = memory_of(backend);
  Buffer<float> z(memory, int64_t(kTexels) * kCapacity, "node depths");
  Buffer<float> v(memory, int64_t(kTexels) * kCapacity, "node values");
  Buffer<int> nodes(memory, kTexels, "nodes"), stored(memory, kTexels, "stored");
  Buffer<int> overflow(memory, kTexels, "overflow");
  Buffer<float> error(memory, kTexels, "error");
  z.fill_zero(), v.fill_zero();
  const View<float> zs = z.view(), vs = v.view(), es = error.view();
  const View<int> ns = nodes.view(), ss = stored.view(), os = overflow.view();
  parallel_for(
      backend, "compress_synthetic_walks", kTexels, DV_KERNEL_LAMBDA(int64_t i) {
        const ArrayNodeSink sink{&zs[i * kCapacity], &vs[i * kCapacity], kCapacity, 0};
        VisibilityCompressor<ArrayNodeSink> compressor(eps, sink);
        synthetic_walk(uint32_t(i), compressor);
        compressor.finish();
        ns[i] = compressor.stats().nodes;
        ss[i] = compressor.sink().count;
        os[i] = compressor.stats().overflow ? 1 : 0;
        es[i] = compressor.stats().max_error;
      });
  if (backend == Backend::cuda) device_synchronize("compress_synthetic_walks");
  return {z.to_vector(),      v.to_vector(),        nodes.to_vector(),
          stored.to_vector(), overflow.to_vector(), error.to_vector()};
}

constexpr float kEpsList[] = {0.0f, 1e-3f, 0.01f, 0.05f};

TEST(VisibilityCompressorBackends, CpuParallelWalksMeetTheBound) {
  for (float eps : kEpsList) {
    const CompressedWalks run = compress_walks(Backend::cpu, eps);
    int overflowed = 0;
    for (int i = 0; i < kTexels; ++i) {
      Samples samples;
      Recorder recorder{&samples};
      synthetic_walk(uint32_t(i), recorder);
      const Compressed full = compress(samples, eps);
      ASSERT_EQ(run.nodes[i], int(full.nodes.size())) << "eps " << eps << " texel " << i;
      ASSERT_EQ(run.stored[i], std::min(run.nodes[i], kCapacity));
      ASSERT_EQ(run.overflow[i] != 0, run.nodes[i] > kCapacity);
      for (int k = 0; k < run.stored[i]; ++k) {
        ASSERT_EQ(run.z[size_t(i) * kCapacity + k], full.nodes[k].z);
        ASSERT_EQ(run.v[size_t(i) * kCapacity + k], full.nodes[k].v);
      }
      overflowed += run.overflow[i];
      if (run.overflow[i]) continue;
      ASSERT_LE(max_error(samples, full.nodes), double(eps)) << "eps " << eps << " texel " << i;
      ASSERT_TRUE(is_monotone(full.nodes));
    }
    // The capacity overflows most texels at eps = 0 and none from eps = 0.01 on.
    if (eps == 0.0f) {
      EXPECT_GT(overflowed, kTexels / 2);
    } else if (eps >= 0.01f) {
      EXPECT_EQ(overflowed, 0) << "eps " << eps;
    }
  }
}

TEST(VisibilityCompressorBackends, CudaGivesTheSameNodes) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "CPU/CUDA parity needs a GPU: " << why;
  for (float eps : kEpsList) {
    const CompressedWalks cpu = compress_walks(Backend::cpu, eps);
    const CompressedWalks gpu = compress_walks(Backend::cuda, eps);
    EXPECT_EQ(gpu.nodes, cpu.nodes) << "eps " << eps;
    EXPECT_EQ(gpu.stored, cpu.stored) << "eps " << eps;
    EXPECT_EQ(gpu.overflow, cpu.overflow) << "eps " << eps;
    EXPECT_EQ(gpu.error, cpu.error) << "eps " << eps;
    EXPECT_EQ(gpu.z, cpu.z) << "eps " << eps;
    EXPECT_EQ(gpu.v, cpu.v) << "eps " << eps;
  }
}

}  // namespace
}  // namespace dv::test
