// The compressor on hand-made inputs whose right answer is known: ramps, single and coincident
// steps, opaque surfaces, eps >= 1, a walk of 10^5 samples, zero-length gaps and equal values,
// a sink that overflows, bad input, and empty streams.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "compressor_test_support.h"

namespace dv::test {
namespace {

std::vector<Node> nodes_of(const Samples& samples, float eps) {
  return compress(samples, eps).nodes;
}

void expect_nodes(const std::vector<Node>& got, const std::vector<Node>& want, float eps) {
  ASSERT_EQ(got.size(), want.size()) << "eps " << eps;
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].z, want[i].z) << "node " << i << " eps " << eps;
    EXPECT_EQ(got[i].v, want[i].v) << "node " << i << " eps " << eps;
  }
}

TEST(VisibilityCompressorCases, LinearRampCompressesToTwoNodes) {
  Samples exact_ramp, rounded_ramp;
  for (int k = 0; k <= 64; ++k) {
    exact_ramp.push_back({1.0f + 0.25f * k, 1.0f - k / 128.0f});
    rounded_ramp.push_back({float(3.1 + 0.37 * k), float(0.93 - 0.0113 * k)});
  }
  for (float eps : {1e-4f, 0.01f, 0.2f}) {
    expect_nodes(nodes_of(exact_ramp, eps), {{1.0f, 1.0f}, {17.0f, 0.5f}}, eps);
    const std::vector<Node> rounded = nodes_of(rounded_ramp, eps);
    ASSERT_EQ(rounded.size(), 2u) << "eps " << eps;
    EXPECT_LE(max_error(rounded_ramp, rounded), 1e-6);
  }
  Samples ramp_then_flat = exact_ramp;
  for (int k = 1; k <= 20; ++k) ramp_then_flat.push_back({17.0f + k, 0.5f});
  for (float eps : {1e-4f, 0.01f})
    expect_nodes(nodes_of(ramp_then_flat, eps), {{1, 1}, {17, 0.5f}}, eps);
  const std::vector<Node> corner_cut = nodes_of(ramp_then_flat, 0.2f);  // a wide band cuts it
  EXPECT_EQ(corner_cut.size(), 2u);
  EXPECT_LE(max_error(ramp_then_flat, corner_cut), 0.2);
  // eps = 0 may keep collinear samples, but is exact and merges the flat tail.
  const std::vector<Node> exact = nodes_of(ramp_then_flat, 0.0f);
  EXPECT_EQ(max_error(ramp_then_flat, exact), 0.0);
  EXPECT_EQ(exact.back().z, 17.0f);
}

TEST(VisibilityCompressorCases, SingleStepGivesTwinNodes) {
  for (float eps : {0.0f, 0.01f, 0.2f}) {
    expect_nodes(nodes_of({{5, 1}, {5, 0.3f}}, eps), {{5, 1}, {5, 0.3f}}, eps);
    const Samples padded = {{1, 1}, {3, 1}, {5, 1}, {5, 0.3f}, {7, 0.3f}, {9, 0.3f}};
    expect_nodes(nodes_of(padded, eps), {{1, 1}, {5, 1}, {5, 0.3f}}, eps);
  }
  // With eps >= 1 the step vanishes into a constant, still within the bound.
  const Samples padded = {{1, 1}, {3, 1}, {5, 1}, {5, 0.3f}, {7, 0.3f}};
  const Compressed wide = compress(padded, 1.0f);
  expect_nodes(wide.nodes, {{1, 1}}, 1.0f);
  EXPECT_FLOAT_EQ(wide.stats.max_error, 0.7f);
}

TEST(VisibilityCompressorCases, StepWithinEpsIsAbsorbed) {
  const Samples small_step = {{1, 1}, {5, 1}, {5, 0.99f}, {9, 0.99f}};
  const Compressed c = compress(small_step, 0.05f);
  expect_nodes(c.nodes, {{1, 1}}, 0.05f);
  EXPECT_NEAR(c.stats.max_error, 0.01f, 1e-6f);
  EXPECT_LE(max_error(small_step, c.nodes), 0.05);
}

TEST(VisibilityCompressorCases, OpaqueSurfaceZeroesEverythingAfter) {
  std::mt19937 rng(8);
  for (int texel = 0; texel < 20;) {
    Samples samples = smoke_texel(rng);
    const Node last = samples.back();
    if (last.v < 0.15f) continue;  // keep the opaque step larger than twice every eps below
    ++texel;
    samples.push_back({last.z, 0.0f});  // the after-side of an opaque crossing at last.z
    for (int k = 1; k <= 50; ++k) samples.push_back({last.z + 0.1f * k, 0.0f});
    for (float eps : {0.0f, 0.01f, 0.05f}) {
      const std::vector<Node> nodes = nodes_of(samples, eps);
      ASSERT_GE(nodes.size(), 3u);
      EXPECT_EQ(nodes.back().z, last.z) << "eps " << eps;
      EXPECT_EQ(nodes.back().v, 0.0f) << "eps " << eps;
      EXPECT_EQ(nodes[nodes.size() - 2].z, last.z) << "a twin at the opaque surface";
      EXPECT_NEAR(nodes[nodes.size() - 2].v, last.v, eps + 1e-7f);
      EXPECT_LE(max_error(samples, nodes), double(eps));
    }
  }
}

TEST(VisibilityCompressorCases, CoincidentSurfacesGiveOneTwin) {
  const Samples inside = {{1, 1},    {4, 1},    {4, 0.6f}, {4, 0.6f},
                          {4, 0.3f}, {4, 0.3f}, {4, 0.1f}, {8, 0.1f}};
  const Samples at_first = {{2, 1}, {2, 0.5f}, {2, 0.5f}, {2, 0.2f}, {3, 0.2f}};
  for (float eps : {0.0f, 0.01f, 0.15f}) {
    expect_nodes(nodes_of(inside, eps), {{1, 1}, {4, 1}, {4, 0.1f}}, eps);
    expect_nodes(nodes_of(at_first, eps), {{2, 1}, {2, 0.2f}}, eps);
  }
}

TEST(VisibilityCompressorCases, EpsOfOneOrMoreNeedsFewNodes) {
  std::mt19937 rng(31);
  for (int texel = 0; texel < 500; ++texel) {
    const Samples samples = random_texel(rng);
    const Compressed two = compress(samples, 2.0f);
    expect_nodes(two.nodes, {samples.front()}, 2.0f);
    const Compressed one = compress(samples, 1.0f);
    EXPECT_LE(one.nodes.size(), 3u);
    EXPECT_LE(max_error(samples, one.nodes), 1.0);
    EXPECT_TRUE(is_monotone(one.nodes));
  }
}

TEST(VisibilityCompressorCases, LongWalkOfAHundredThousandSamples) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Samples samples;
  double t = 1.0, density = 0.0;
  for (int i = 0; i < 100000; ++i) {
    density = std::max(0.0, density + 0.05 * (u(rng) - 0.5));
    if (i > 0) t *= std::exp(-1e-5 * density);
    samples.push_back({float(1.0 + 1e-3 * i), float(t)});
    if (i % 20000 == 19999) samples.push_back({samples.back().z, float(t *= 0.7)});
  }
  for (float eps : {0.0f, 1e-4f, 0.01f}) {
    const Compressed c = compress(samples, eps);
    EXPECT_LE(max_error(samples, c.nodes), double(eps)) << "eps " << eps;
    EXPECT_TRUE(is_monotone(c.nodes));
    if (eps >= 0.01f) {
      EXPECT_LT(c.nodes.size(), 40u);
    }
  }
}

TEST(VisibilityCompressorCases, ZeroLengthGapsAndEqualValues) {
  const Samples constant = {{1, 1}, {1, 1}, {2, 1}, {2, 1}, {3, 1}, {7, 1}};
  const Samples gap_step = {{1, 1}, {2, 1}, {2, 0.5f}, {3, 0.5f}};
  const Samples plateau = {{0, 1}, {1, 0.8f}, {2, 0.8f}, {3, 0.8f}, {4, 0.6f}};
  for (float eps : {0.0f, 0.01f}) {
    expect_nodes(nodes_of(constant, eps), {{1, 1}}, eps);
    expect_nodes(nodes_of(gap_step, eps), {{1, 1}, {2, 1}, {2, 0.5f}}, eps);
    expect_nodes(nodes_of(plateau, eps), {{0, 1}, {1, 0.8f}, {3, 0.8f}, {4, 0.6f}}, eps);
  }
}

TEST(VisibilityCompressorCases, OverflowStopsEmittingButKeepsCounting) {
  Samples staircase;
  for (int k = 0; k < 4; ++k) staircase.push_back({float(k), 1.0f - 0.2f * k});
  for (int k = 0; k < 4; ++k) staircase.push_back({float(k + 4), 0.4f - 0.04f * k * k});
  const std::vector<Node> all = nodes_of(staircase, 0.0f);
  ASSERT_GT(all.size(), 4u);

  float z[3], v[3];
  VisibilityCompressor<ArrayNodeSink> small(0.0f, ArrayNodeSink{z, v, 3});
  VisibilityCompressor<CountingNodeSink> counting(0.0f);
  for (const Node& s : staircase) small.push(s.z, s.v), counting.push(s.z, s.v);
  small.finish(), counting.finish();
  EXPECT_TRUE(small.stats().overflow);
  EXPECT_EQ(small.stats().nodes, int(all.size()));
  EXPECT_EQ(small.sink().count, 3);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(z[i], all[i].z);
    EXPECT_EQ(v[i], all[i].v);
  }
  EXPECT_FALSE(counting.stats().overflow);
  EXPECT_EQ(counting.sink().count, int(all.size()));
}

TEST(VisibilityCompressorCases, BadInputIsSanitised) {
  std::vector<Node> got;
  VisibilityCompressor<VectorSink> c(0.0f, VectorSink{&got});
  c.push(1.0f, 1.5f);  // above 1: clamped
  c.push(2.0f, 0.9f);
  c.push(2.5f, 0.95f);     // visibility rising: clamped to 0.9
  c.push(1.5f, 0.4f);      // depth going back: raised to 2.5
  c.push(NAN, 0.1f);       // ignored
  c.push(3.0f, NAN);       // ignored
  c.push(INFINITY, 0.0f);  // ignored
  c.push(4.0f, -1.0f);     // below 0: clamped
  c.finish();
  c.push(9.0f, 0.0f);  // after finish: ignored
  c.finish();
  expect_nodes(got, nodes_of({{1, 1}, {2, 0.9f}, {2.5f, 0.9f}, {2.5f, 0.4f}, {4, 0}}, 0.0f), 0);
  EXPECT_TRUE(is_monotone(got));
  EXPECT_EQ(got.back().v, 0.0f);
}

TEST(VisibilityCompressorCases, NegativeOrNanEpsActsAsZero) {
  const Samples ramp = {{0, 1}, {1, 0.75f}, {2, 0.5f}, {3, 0.4f}};
  for (float eps : {-1.0f, NAN}) {
    const Compressed c = compress(ramp, eps);
    EXPECT_EQ(max_error(ramp, c.nodes), 0.0);
    EXPECT_EQ(c.stats.max_error, 0.0f);
  }
}

TEST(VisibilityCompressorCases, EmptyStreamHasNoNodes) {
  const Compressed c = compress({}, 0.05f);
  EXPECT_TRUE(c.nodes.empty());
  EXPECT_EQ(c.stats.nodes, 0);
  EXPECT_EQ(c.stats.max_error, 0.0f);
}

}  // namespace
}  // namespace dv::test
