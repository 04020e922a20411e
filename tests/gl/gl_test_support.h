// What the GL voxelizer tests share: a fixture that makes a headless OpenGL 4.5 context or
// skips with the reason, and counting (and printing the first few of) the voxels set in one
// grid but not the other.
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cstdio>
#include <memory>
#include <string>

#include "gl/egl_context.h"
#include "strategies/voxelizer/voxel_grid.h"

namespace dv::test {

class GlContextTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string why;
    context_ = gl::EglContext::create_headless(&why);
    if (!context_) GTEST_SKIP() << "no headless OpenGL 4.5 here: " << why;
  }
  std::unique_ptr<gl::EglContext> context_;
};

inline int64_t count_differences(const VoxelGrid& cpu, const VoxelGrid& gl,
                                 const std::string& label) {
  const std::vector<uint32_t> wa = cpu.words(), wb = gl.words();
  const ivec3 r = cpu.spec().res;
  int64_t differ = 0;
  for (size_t i = 0; i < wa.size(); ++i) {
    const uint32_t d = wa[i] ^ wb[i];
    if (!d) continue;
    if (differ < 5) {
      const int64_t x = int64_t(i) % r.x, y = int64_t(i) / r.x % r.y, k = int64_t(i) / r.x / r.y;
      std::printf("  %s: column (%lld, %lld) word %lld: cpu %08x gl %08x\n", label.c_str(),
                  (long long)x, (long long)y, (long long)k, wa[i], wb[i]);
    }
    differ += std::popcount(d);
  }
  return differ;
}

}  // namespace dv::test
