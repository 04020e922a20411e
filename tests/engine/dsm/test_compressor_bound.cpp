// The compressor's guarantee on random texels: |V' - V| <= eps everywhere (both sides of every
// step), V' monotone in [0, 1], the reported error an upper bound on the error reached and at
// most eps, eps = 0 exact, and fewer nodes (never more) as eps grows.
#include <gtest/gtest.h>

#include <random>

#include "compressor_test_support.h"

namespace dv::test {
namespace {

constexpr float kEpsList[] = {0.0f, 1e-4f, 0.01f, 0.05f, 0.2f, 1.0f, 2.0f};
constexpr int kTexels = 3000;

TEST(VisibilityCompressorBound, RandomTexelsStayWithinEps) {
  for (float eps : kEpsList) {
    std::mt19937 rng(12345);
    double worst_gap = 0.0;
    for (int texel = 0; texel < kTexels; ++texel) {
      const Samples samples = random_texel(rng);
      const Compressed c = compress(samples, eps);
      const double error = max_error(samples, c.nodes);
      ASSERT_LE(error, double(eps)) << "eps " << eps << " texel " << texel;
      ASSERT_TRUE(is_monotone(c.nodes)) << "eps " << eps << " texel " << texel;
      ASSERT_EQ(c.stats.nodes, int(c.nodes.size()));
      ASSERT_FALSE(c.stats.overflow);
      ASSERT_GE(c.stats.nodes, 1);
      EXPECT_EQ(c.nodes.front().z, samples.front().z);
      ASSERT_LE(c.stats.max_error, eps);
      ASSERT_GE(double(c.stats.max_error), error - 1e-6) << "eps " << eps << " texel " << texel;
      worst_gap = std::max(worst_gap, error);
    }
    if (eps == 0.0f) {
      EXPECT_EQ(worst_gap, 0.0);
    }
  }
}

TEST(VisibilityCompressorBound, EpsZeroKeepsEveryBendExactly) {
  std::mt19937 rng(777);
  for (int texel = 0; texel < 500; ++texel) {
    const Samples samples = random_texel(rng);
    const Compressed c = compress(samples, 0.0f);
    ASSERT_EQ(max_error(samples, c.nodes), 0.0) << "texel " << texel;
    EXPECT_EQ(c.stats.max_error, 0.0f);
    EXPECT_LE(c.nodes.size(), samples.size());
  }
}

// Far from the light float32 depths are coarse: tiny gaps, steep drops, nodes between them.
TEST(VisibilityCompressorBound, RoundingFarFromTheLightKeepsTheBound) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int texel = 0; texel < 400; ++texel) {
    Samples samples;
    double z = 1e4 * (1.0 + u(rng)), t = 1.0;
    for (int i = 0; i < 300; ++i) {
      samples.push_back({float(z), float(t)});
      z += std::ldexp(1.0, -9 + int(u(rng) * 12.0));  // 1/512 .. 4 (ulp of 1e4 is 1/1024)
      t *= std::exp(-(u(rng) < 0.1 ? 3.0 : 0.02) * u(rng));
    }
    for (float eps : {1e-5f, 1e-4f, 3e-3f, 0.05f}) {
      const Compressed c = compress(samples, eps);
      ASSERT_LE(max_error(samples, c.nodes), double(eps)) << "eps " << eps << " texel " << texel;
      ASSERT_TRUE(is_monotone(c.nodes));
    }
  }
}

TEST(VisibilityCompressorBound, NodeCountNeverGrowsWithEps) {
  std::mt19937 rng(2024);
  for (int texel = 0; texel < 1000; ++texel) {
    const Samples samples = texel % 2 ? random_texel(rng) : smoke_texel(rng);
    int previous = int(samples.size()) + 1;
    for (float eps : kEpsList) {
      const int nodes = compress(samples, eps).stats.nodes;
      ASSERT_LE(nodes, previous) << "eps " << eps << " texel " << texel;
      previous = nodes;
    }
  }
}

TEST(VisibilityCompressorBound, SmokeNeedsFewNodes) {
  std::mt19937 rng(5);
  double nodes_001 = 0.0, nodes_005 = 0.0, samples = 0.0;
  const int texels = 300;
  for (int texel = 0; texel < texels; ++texel) {
    const Samples s = smoke_texel(rng);
    samples += double(s.size());
    nodes_001 += compress(s, 0.01f).stats.nodes;
    nodes_005 += compress(s, 0.05f).stats.nodes;
  }
  EXPECT_LT(nodes_001, 0.1 * samples);
  EXPECT_LT(nodes_005, nodes_001);
  EXPECT_GT(nodes_005, 2.0 * texels);  // a smooth decay still bends: not a single line
}

}  // namespace
}  // namespace dv::test
