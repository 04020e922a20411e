// Hard cases of the visibility compressor that tests/engine/dsm does not already hold (those are
// labelled `hard` there): a tiny eps (1e-7, below float32's spacing near 1), a million samples
// of opacity accumulating towards 1 (into float32's subnormals and 0), and coincident surfaces
// at one depth in every order, opaque ones included. Expectations: the exact bound |V' - V| <=
// eps in double over the float32 nodes (compressor_test_support.h evaluates both), monotone,
// finite, non-negative; products of (1 - alpha) in double for the coincident surfaces.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "tests/engine/dsm/compressor_test_support.h"

namespace dv::test {
namespace {

bool all_finite(const std::vector<Node>& nodes) {
  return std::all_of(nodes.begin(), nodes.end(),
                     [](const Node& n) { return std::isfinite(n.z) && std::isfinite(n.v); });
}

TEST(HardCompression, TinyEpsKeepsTheBoundOnRandomTexels) {
  std::mt19937 rng(1414);
  for (int texel = 0; texel < 400; ++texel) {
    const Samples samples = random_texel(rng);
    const Compressed c = compress(samples, 1e-7f);
    ASSERT_LE(max_error(samples, c.nodes), 1e-7) << "texel " << texel;
    ASSERT_TRUE(is_monotone(c.nodes)) << "texel " << texel;
    ASSERT_LE(c.stats.max_error, 1e-7f);
  }
}

// Optical depth 2e-4 per sample over 10^6 samples (200 in all): visibility falls through
// float32's normal range (1.2e-38 at optical depth 87) into subnormals and rounds to 0.
TEST(HardCompression, AMillionSamplesTowardsOpacityOne) {
  Samples samples;
  samples.reserve(1000000);
  double optical_depth = 0.0;
  for (int i = 0; i < 1000000; ++i) {
    samples.push_back({float(1.0 + 1e-5 * i), float(std::exp(-optical_depth))});
    optical_depth += 2e-4;
  }
  ASSERT_EQ(samples.back().v, 0.0f);
  for (float eps : {0.0f, 1e-7f, 1e-3f, 0.05f}) {
    const Compressed c = compress(samples, eps);
    ASSERT_FALSE(c.nodes.empty());
    EXPECT_TRUE(all_finite(c.nodes)) << "eps " << eps;
    EXPECT_TRUE(is_monotone(c.nodes)) << "eps " << eps;  // also: no negative visibility
    EXPECT_LE(max_error(samples, c.nodes), double(eps)) << "eps " << eps;
    EXPECT_LE(c.nodes.back().v, eps) << "eps " << eps;  // opacity reaches 1 within eps
    EXPECT_FALSE(c.stats.overflow);
  }
}

// Four surfaces at depth 3 (one opaque in the second set) crossed in each of the 24 orders:
// every order ends at the same product, within one float32 rounding per factor, and gives
// one twin at depth 3 (eps 0) whatever the order.
TEST(HardCompression, CoincidentSurfacesInAnyOrder) {
  for (const std::array<double, 4>& set :
       {std::array<double, 4>{0.3, 0.5, 0.05, 0.7}, std::array<double, 4>{0.3, 1.0, 0.5, 0.2}}) {
    double product = 1.0;
    for (double alpha : set) product *= 1.0 - alpha;
    std::array<int, 4> order = {0, 1, 2, 3};
    do {
      Samples samples = {{1.0f, 1.0f}, {3.0f, 1.0f}};
      float v = 1.0f;
      for (int k : order) {
        samples.push_back({3.0f, v});
        v = float(double(v) * (1.0 - set[size_t(k)]));
        samples.push_back({3.0f, v});
      }
      samples.push_back({5.0f, v});
      for (float eps : {0.0f, 0.01f}) {
        const Compressed c = compress(samples, eps);
        ASSERT_EQ(c.nodes.size(), 3u) << "eps " << eps;
        EXPECT_EQ(c.nodes[1].z, 3.0f);
        EXPECT_EQ(c.nodes[1].v, 1.0f);
        EXPECT_EQ(c.nodes[2].z, 3.0f);
        EXPECT_NEAR(c.nodes[2].v, product, 4 * 6e-8) << "eps " << eps;
        if (product == 0.0) {
          EXPECT_EQ(c.nodes[2].v, 0.0f);
        }
        EXPECT_LE(max_error(samples, c.nodes), double(eps));
      }
    } while (std::next_permutation(order.begin(), order.end()));
  }
}

// Opacity-1 samples from the start: a texel whose first crossing is opaque holds the twin
// (1 then 0) and nothing after it, for every eps including those of 1 and more.
TEST(HardCompression, OpaqueFirstSampleEndsTheFunction) {
  Samples samples = {{2.0f, 1.0f}, {2.0f, 0.0f}};
  for (int k = 1; k <= 1000; ++k) samples.push_back({2.0f + 0.01f * k, 0.0f});
  for (float eps : {0.0f, 1e-7f, 0.3f}) {
    const Compressed c = compress(samples, eps);
    ASSERT_EQ(c.nodes.size(), 2u) << "eps " << eps;
    EXPECT_EQ(c.nodes[0].z, 2.0f);
    EXPECT_EQ(c.nodes[0].v, 1.0f);
    EXPECT_EQ(c.nodes[1].z, 2.0f);
    EXPECT_EQ(c.nodes[1].v, 0.0f);
  }
  const Compressed wide = compress(samples, 1.0f);  // eps 1 may drop the step, within the bound
  EXPECT_LE(max_error(samples, wide.nodes), 1.0);
  EXPECT_TRUE(is_monotone(wide.nodes));
}

}  // namespace
}  // namespace dv::test
