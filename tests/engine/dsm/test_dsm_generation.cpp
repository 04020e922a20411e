// Deep-shadow-map generation on real walks: the error bound |V' - V| <= eps against the walk's
// own samples over every texel of every face (spot, omni, directional) of the repository's
// scenes and random scenes, for eps 0 (every bend kept), small, large and >= 1; monotone
// output; long walks, opacity-1 and coincident surfaces; and generation records.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "tests/engine/dsm/dsm_test_support.h"

namespace dv {
namespace {

using test::max_error;
using test::RecordingTarget;

// The compressor's bound holds up to float rounding of the evaluation (values are floats).
constexpr double kEvalSlack = 2e-6;

void check_every_texel(const SceneData& data, int res, float eps) {
  const DsmGeneration generation(data, Backend::cpu, {.resolution = res});
  const DsmGenerator& g = generation.generator();
  int64_t texels = 0, non_empty = 0;
  for (int64_t i = 0; i < g.thread_count(); ++i) {
    DsmTexel t;
    if (!g.texel_of_thread(i, t)) continue;
    RecordingTarget target(eps);
    double final_v = 1.0;
    const WalkStatus status = g.walk(t, eps, target, final_v);
    target.compressor.finish();
    ASSERT_FALSE(status.overflow);
    ++texels;
    if (target.samples.empty()) continue;
    ++non_empty;
    const double err = max_error(target.samples, target.nodes);
    ASSERT_LE(err, double(eps) + kEvalSlack)
        << "face " << t.face << " texel " << t.x << "," << t.y << " eps " << eps;
    ASSERT_TRUE(test::is_monotone(target.nodes));
    ASSERT_LE(target.compressor.stats().max_error, eps);
    // Generation's own result for the texel agrees with the recorded run.
    const DsmTexelResult<CountingNodeSink> r = g.generate(t, eps, CountingNodeSink{});
    ASSERT_EQ(r.record.nodes, int(target.nodes.size()));
    ASSERT_EQ(r.record.flags, 0u);
  }
  EXPECT_EQ(texels, g.texel_count());
  EXPECT_GT(non_empty, texels / 50);  // the casters cover a good part of the maps
}

class BoundOnScenes : public ::testing::TestWithParam<std::tuple<const char*, float>> {};

TEST_P(BoundOnScenes, EveryTexelWithinEps) {
  const auto [file, eps] = GetParam();
  const SceneData data(test::scene_file(file), Memory::host);
  check_every_texel(data, 20, eps);
}

INSTANTIATE_TEST_SUITE_P(Scenes, BoundOnScenes,
                         ::testing::Combine(::testing::Values("demo.json", "translucent-boxes.json",
                                                              "intersecting-volumes.json",
                                                              "ct-phantom.json"),
                                            ::testing::Values(0.0f, 0.01f, 0.1f, 1.5f)));

class BoundOnRandomScenes : public ::testing::TestWithParam<std::tuple<unsigned, float>> {};

TEST_P(BoundOnRandomScenes, EveryTexelWithinEps) {
  const auto [seed, eps] = GetParam();
  const SceneData data(test::random_scene(seed), Memory::host);
  check_every_texel(data, 16, eps);
}

INSTANTIATE_TEST_SUITE_P(Random, BoundOnRandomScenes,
                         ::testing::Combine(::testing::Values(1u, 2u, 3u),
                                            ::testing::Values(0.0f, 0.05f, 1.0f)));

// A light above a stack of quads: one texel-centre ray through all of them.
SceneData quad_stack(int count, double alpha, bool coincident_pairs) {
  test::SceneBuilder b;
  for (int i = 0; i < count; ++i) {
    TriangleMesh q = make_quad(4.0);
    const double y = coincident_pairs ? double(i / 2) * 0.01 : double(i) * 0.01;
    for (dvec3& v : q.positions) v.y = y;
    b.add(std::move(q), alpha);
  }
  b.spot(dvec3(0.0, 10.0, 0.0), dvec3(0.0, -1.0, 0.0), 10.0);
  return b.build();
}

std::vector<test::Node> centre_nodes(const SceneData& data, float eps, int res,
                                     test::Samples* samples = nullptr) {
  const DsmGeneration generation(data, Backend::cpu, {.resolution = res});
  const DsmGenerator& g = generation.generator();
  // Off the axis by (1.5, 0.5) texels: clear of the quads' diagonals.
  DsmTexel t{0, res / 2 + 1, res / 2, int64_t(res / 2) * res + res / 2 + 1};
  RecordingTarget target(eps);
  double final_v = 1.0;
  g.walk(t, eps, target, final_v);
  target.compressor.finish();
  if (samples) *samples = target.samples;
  return target.nodes;
}

TEST(DsmGeneration, LongWalkWithEpsZeroKeepsEveryStep) {
  const SceneData data = quad_stack(600, 0.004, false);
  test::Samples samples;
  const std::vector<test::Node> nodes = centre_nodes(data, 0.0f, 8, &samples);
  EXPECT_EQ(samples.size(), 1200u);  // twin samples per quad
  EXPECT_EQ(nodes.size(), 1200u);    // eps 0: every step stays a step
  EXPECT_EQ(max_error(samples, nodes), 0.0);
  EXPECT_NEAR(nodes.back().v, std::pow(1.0 - 0.004, 600), 1e-5);
}

TEST(DsmGeneration, LargeEpsCollapsesTheFunction) {
  const SceneData data = quad_stack(600, 0.004, false);
  test::Samples samples;
  const std::vector<test::Node> nodes = centre_nodes(data, 0.2f, 8, &samples);
  EXPECT_LE(max_error(samples, nodes), 0.2 + kEvalSlack);
  EXPECT_LT(nodes.size(), 20u);
  EXPECT_EQ(centre_nodes(data, 1.0f, 8).size(), 1u);  // eps >= 1 admits V' = 1
}

TEST(DsmGeneration, OpaqueSurfaceEndsTheWalk) {
  const SceneData data = quad_stack(3, 1.0, false);
  test::Samples samples;
  const std::vector<test::Node> nodes = centre_nodes(data, 0.0f, 8, &samples);
  ASSERT_EQ(samples.size(), 2u);  // the first quad takes all light; the walk stops there
  EXPECT_EQ(samples[1].v, 0.0f);
  ASSERT_EQ(nodes.size(), 2u);
  EXPECT_EQ(nodes[0].z, nodes[1].z);
  EXPECT_EQ(nodes[1].v, 0.0f);
}

TEST(DsmGeneration, CoincidentSurfacesGiveOneStep) {
  const SceneData data = quad_stack(4, 0.5, true);  // two pairs of coincident quads
  test::Samples samples;
  const std::vector<test::Node> nodes = centre_nodes(data, 0.0f, 8, &samples);
  ASSERT_EQ(nodes.size(), 4u);  // one twin per depth
  EXPECT_EQ(nodes[0].v, 1.0f);
  EXPECT_NEAR(nodes[1].v, 0.25, 1e-6);
  EXPECT_NEAR(nodes[3].v, 0.0625, 1e-6);
  EXPECT_EQ(max_error(samples, nodes), 0.0);
}

}  // namespace
}  // namespace dv

namespace dv {
namespace {

// The exact average of the sub-rays' sampled functions of texel t (walked here independently,
// eps 0) against the pre-filtered texel's nodes.
double prefilter_error(const DsmGenerator& g, const DsmTexel& t, float eps,
                       std::vector<test::Node>& nodes) {
  nodes.clear();
  g.generate(t, eps, test::VectorSink{&nodes});
  const ShadowFace& f = g.faces[t.face];
  const int side = g.subrays == 16 ? 4 : (g.subrays == 9 ? 3 : 2);
  std::vector<test::Samples> rays;
  std::vector<double> depths;
  for (int k = 0; k < g.subrays; ++k) {
    const PixelRay ray =
        image_point_ray(f.projection, t.x + (k % side + subray_jitter(t.index, k, 0)) / side,
                        t.y + (k / side + subray_jitter(t.index, k, 1)) / side);
    const NearPlaneStart front =
        start_at_near_plane(g.scene, f.projection, ray, g.ray_media[t.face]);
    RecordingTarget target(0.0f);
    VisibilityPayload<RecordingTarget> payload{g.scene, target, ray.origin, ray.direction, eps};
    const BvhFragments fragments{&g.scene, make_sheared_ray(ray.origin, ray.direction), 1e300};
    walk_fragments(g.scene, fragments, front.status.inside, front.t, front.t, 1e300, payload);
    for (const test::Node& n : target.samples) depths.push_back(n.z);
    rays.push_back(target.samples);
  }
  for (const test::Node& n : nodes) depths.push_back(n.z);
  double worst = 0.0;
  for (double z : depths)
    for (bool right : {false, true}) {
      double average = 0.0;
      for (const test::Samples& r : rays) average += test::evaluate(r, z, right) / rays.size();
      worst = std::max(worst, std::abs(average - test::evaluate(nodes, z, right)));
    }
  return worst;
}

TEST(DsmPrefilter, WithinEpsOfTheSubrayAverage) {
  for (unsigned seed : {1u, 2u}) {
    const SceneData data(test::random_scene(seed), Memory::host);
    DsmGeneration generation(data, Backend::cpu, {.resolution = 12, .subrays = 4});
    const DsmGenerator& g = generation.generator();
    int64_t partial = 0;
    for (int64_t i = 0; i < g.thread_count(); ++i) {
      DsmTexel t;
      if (!g.texel_of_thread(i, t)) continue;
      std::vector<test::Node> nodes;
      const double err = prefilter_error(g, t, 0.05f, nodes);
      ASSERT_LE(err, 0.05 + kEvalSlack) << "seed " << seed << " texel " << t.index;
      ASSERT_TRUE(test::is_monotone(nodes));
      // Some texels straddle an edge: their last value is neither lit nor fully behind one.
      if (!nodes.empty() && nodes.back().v > 0.01f && nodes.back().v < 0.99f) ++partial;
    }
    EXPECT_GT(partial, 10);
  }
}

TEST(DsmPrefilter, OpaqueEdgeGivesFractionalVisibility) {
  test::SceneBuilder b;
  b.add(make_box(dvec3(-2.0, 0.0, -2.0), dvec3(0.05, 0.2, 2.0)), 1.0);  // edge inside a texel
  b.spot(dvec3(0.0, 5.0, 0.0), dvec3(0.0, -1.0, 0.0), 20.0);
  const SceneData data = b.build();
  DsmGeneration plain(data, Backend::cpu, {.resolution = 16}),
      filtered(data, Backend::cpu, {.resolution = 16, .subrays = 16});
  // Texels around the edge: unfiltered all or nothing, pre-filtered a fraction for the column
  // the edge runs through.
  int straddling = 0;
  for (int y = 2; y < 14; ++y) {
    for (int x = 6; x < 10; ++x) {
      const DsmTexel t{0, x, y, int64_t(y) * 16 + x};
      std::vector<test::Node> a, f;
      plain.generator().generate(t, 0.0f, test::VectorSink{&a});
      filtered.generator().generate(t, 0.0f, test::VectorSink{&f});
      const float last_plain = a.empty() ? 1.0f : a.back().v;
      const float last_filtered = f.empty() ? 1.0f : f.back().v;
      EXPECT_TRUE(last_plain == 0.0f || last_plain == 1.0f);
      if (last_filtered > 0.0f && last_filtered < 1.0f) ++straddling;
    }
  }
  EXPECT_GT(straddling, 0);
}

}  // namespace
}  // namespace dv
