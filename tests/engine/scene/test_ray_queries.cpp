// Ray queries: the BVH finds exactly the hits a brute-force loop finds, next_hit walks them in
// (t, triangle) order, the entering flag follows outward normals, and closed meshes are
// watertight (every ray from outside to outside crosses an even number of times).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "engine/scene/ray_query.h"
#include "tests/support/scene_builder.h"

namespace dv {
namespace {

using test::SceneBuilder;

std::vector<RayHit> brute_force_hits(const SceneView& s, const ShearedRay& r, double t_max) {
  std::vector<RayHit> hits;
  for (uint32_t i = 0; i < uint32_t(s.triangles.size); ++i) {
    double t;
    bool entering;
    if (intersect_scene_triangle(s, r, i, t, entering) && t > 0.0 && t <= t_max)
      hits.push_back({t, i, entering});
  }
  return hits;
}

bool by_t(const RayHit& a, const RayHit& b) {
  return a.t < b.t || (a.t == b.t && a.triangle < b.triangle);
}

TEST(RayQueries, EnteringFollowsOutwardNormals) {
  SceneBuilder b;
  b.add(make_box({-1, -1, -1}, {1, 1, 1}));
  b.omni({0, 5, 0});
  const SceneData data = b.build();
  const ShearedRay r = make_sheared_ray({0.2, 5.0, 0.1}, {0.0, -1.0, 0.0});
  std::vector<RayHit> hits = brute_force_hits(data.view(), r, 100.0);
  std::sort(hits.begin(), hits.end(), by_t);
  ASSERT_EQ(hits.size(), 2u);
  EXPECT_TRUE(hits[0].entering);
  EXPECT_FALSE(hits[1].entering);
  EXPECT_DOUBLE_EQ(hits[0].t, 4.0);
  EXPECT_DOUBLE_EQ(hits[1].t, 6.0);
}

TEST(RayQueries, BvhAndNextHitMatchBruteForceAndMeshesAreWatertight) {
  SceneBuilder b;
  b.add(make_icosphere(1.0, 4));
  Object& torus = b.add(make_torus(0.8, 0.3, 40, 20));
  torus.transform[3] = dvec4(0.5, 0.2, 0.1, 1.0);
  b.add(make_box({-2, -2, -2}, {-1.5, 2, 2}));
  b.omni({0, 5, 0});
  const SceneData data = b.build();
  const SceneView& s = data.view();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int ray = 0; ray < 300; ++ray) {
    // Rays from outside the scene to outside the scene, many through vertices' neighbourhoods.
    const dvec3 from = glm::normalize(dvec3(u(rng), u(rng), u(rng))) * 6.0;
    const dvec3 to = dvec3(u(rng), u(rng), u(rng)) * 0.9;
    const dvec3 dir = glm::normalize(to - from);
    const ShearedRay r = make_sheared_ray(from, dir);
    std::vector<RayHit> expected = brute_force_hits(s, r, 12.0);
    std::sort(expected.begin(), expected.end(), by_t);
    std::vector<RayHit> found;
    for_each_hit(s, r, 0.0, 12.0, [&](const RayHit& h) { return found.push_back(h), true; });
    std::sort(found.begin(), found.end(), by_t);
    ASSERT_EQ(found.size(), expected.size());
    std::vector<RayHit> walked;
    RayHit h{};
    double t = 0.0;
    int64_t tri = -1;
    while (next_hit(s, r, t, tri, 12.0, h)) walked.push_back(h), t = h.t, tri = h.triangle;
    ASSERT_EQ(walked.size(), expected.size());
    int depth = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
      EXPECT_EQ(found[i].triangle, expected[i].triangle);
      EXPECT_EQ(walked[i].triangle, expected[i].triangle);
      depth += expected[i].entering ? 1 : -1;
      EXPECT_GE(depth, 0);
    }
    EXPECT_EQ(depth, 0) << "ray " << ray;
    EXPECT_EQ(expected.size() % 2, 0u) << "ray " << ray;
  }
}

TEST(RayQueries, RaysThroughVerticesAndEdgesCrossOnce) {
  // Rays aimed exactly at mesh vertices and edge midpoints of a closed icosphere still see an
  // even number of crossings with alternating entering flags.
  SceneBuilder b;
  b.add(make_icosphere(1.0, 2));
  b.omni({0, 5, 0});
  const SceneData data = b.build();
  const SceneView& s = data.view();
  int rays = 0;
  for (int64_t v = 0; v < s.vertices.size; ++v) {
    const dvec3 target = s.vertices[v];
    const dvec3 from = target * 4.0 + dvec3(0.0, 0.0, 0.0);
    const ShearedRay r = make_sheared_ray(from, glm::normalize(target - from));
    std::vector<RayHit> hits = brute_force_hits(s, r, 20.0);
    std::sort(hits.begin(), hits.end(), by_t);
    ASSERT_EQ(hits.size(), 2u) << "vertex " << v;
    EXPECT_TRUE(hits[0].entering);
    EXPECT_FALSE(hits[1].entering);
    ++rays;
  }
  EXPECT_GT(rays, 100);
}

}  // namespace
}  // namespace dv
