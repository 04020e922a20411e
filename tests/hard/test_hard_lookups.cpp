// Hard cases of deep-shadow-map lookups, nearest and bilinear, on the CPU and CUDA: the spot
// cone's edge (points just inside sit in the outer half of the map's border texels), the seam
// between omni faces (continuity across it, on it and at a cube corner), and points outside a
// directional map (lit), and between two clusters' maps. Expectations are closed forms, (1 - alpha)
// behind a translucent quad, checked against the exact oracle too; lookups must meet them within
// eps. Depth exactly on a node, before the first and after the last, and twin nodes are
// DsmLookups.ClampsAndTwinRule (tests/strategies/storage, labelled hard).
#include <gtest/gtest.h>

#include <cmath>

#include "tests/hard/hard_test_support.h"

namespace dv::test {
namespace {

constexpr double kAlpha = 0.5;
constexpr float kEps = 0.01f;

// Expects the oracle (CPU) and the maps, nearest and bilinear, to give `expected` at every point.
void expect_lookups(const Scene& scene, Backend backend, int res, const std::vector<dvec3>& points,
                    const std::vector<double>& expected, const char* what) {
  Scene host_scene = scene;
  validate_scene(host_scene);
  const SceneData host(host_scene, Memory::host);
  for (size_t i = 0; i < points.size(); ++i)
    ASSERT_NEAR(oracle_at(host, 0, points[i]), expected[i], 1e-12) << what << " point " << i;
  for (bool bilinear : {false, true}) {
    const HardMaps m = generate_maps(scene, backend, unbiased_settings(kEps, res, bilinear));
    const std::vector<double> got = dsm_lookups(m, backend, points, 0);
    for (size_t i = 0; i < points.size(); ++i)
      EXPECT_NEAR(got[i], expected[i], kEps + 1e-6)
          << what << (bilinear ? " bilinear" : " nearest") << " point " << i << " at "
          << points[i].x << "," << points[i].y << "," << points[i].z;
  }
}

class HardLookups : public HardOnBackends {};

// A spot light 5 above a translucent quad at y = 1 (cutoff 30 degrees, a 16 x 16 map): points
// at y = 0 at 0.999 of the cutoff angle in eight directions lie in the outer half of border
// texels (along the axes) or near the map's corners' diagonal; 1.001 of it is outside (T = 0).
TEST_P(HardLookups, SpotConeEdgeAndMapBorder) {
  SceneBuilder b;
  b.add(quad_at(1.0, 20.0), kAlpha);
  b.spot(dvec3(0.0, 5.0, 0.0), dvec3(0.0, -1.0, 0.0), 30.0);
  std::vector<dvec3> points;
  std::vector<double> expected;
  const double pi = std::acos(-1.0), cutoff = 30.0 * pi / 180.0;
  for (double fraction : {0.999, 1.001})
    for (int k = 0; k < 8; ++k) {
      const double r = 5.0 * std::tan(fraction * cutoff), phi = k * pi / 4.0;
      points.push_back(dvec3(r * std::cos(phi), 0.0, r * std::sin(phi)));
      expected.push_back(fraction < 1.0 ? 1.0 - kAlpha : 0.0);
    }
  expect_lookups(b.scene, GetParam(), 16, points, expected, "spot cone edge");
}

// An omni light at the origin above a translucent quad at y = -1: on the plane y = -2 the
// seam between the -Y and +X faces is x = 2 and between -Y and +Z it is z = 2; points cross
// them in steps of 0.01, lie on them and on the cube corner (2, -2, 2). T = 0.5 everywhere, so
// a jump across a seam is a lookup error.
TEST_P(HardLookups, OmniFaceSeamsAreContinuous) {
  SceneBuilder b;
  b.add(quad_at(-1.0, 20.0), kAlpha);
  b.omni(dvec3(0.0));
  std::vector<dvec3> points;
  for (int k = -10; k <= 10; ++k) {
    points.push_back(dvec3(2.0 + 0.01 * k, -2.0, 0.3));
    points.push_back(dvec3(-0.4, -2.0, 2.0 + 0.01 * k));
    points.push_back(dvec3(2.0 + 0.01 * k, -2.0, 2.0 + 0.01 * k));
  }
  points.push_back(dvec3(-2.0, -2.0, -2.0));
  expect_lookups(b.scene, GetParam(), 16, points, std::vector<double>(points.size(), 0.5),
                 "omni seam");
}

// A directional light straight down on a 2 x 2 quad: the map is fitted to the quad, so points
// beside it project outside the map and must be lit, however far out.
TEST_P(HardLookups, OutsideADirectionalMapIsLit) {
  SceneBuilder b;
  b.add(quad_at(1.0, 2.0), kAlpha);
  b.directional(dvec3(0.0, -1.0, 0.0));
  const std::vector<dvec3> points = {{0.5, 0.0, 0.5},  {-0.9, 0.0, 0.9}, {1.2, 0.0, 0.0},
                                     {0.0, 0.0, -1.5}, {3.0, -5.0, 3.0}, {100.0, 0.0, -100.0}};
  expect_lookups(b.scene, GetParam(), 16, points, {0.5, 0.5, 1.0, 1.0, 1.0, 1.0},
                 "outside the map");
}

// Two translucent quads 8 apart under one spot light, in two clusters (Knecht eq. 3.12: the
// product over the cluster faces whose window holds the point): points under either quad see
// only its face (0.5), points between the clusters lie in no window and are lit.
TEST_P(HardLookups, BetweenTwoClusters) {
  SceneBuilder b;
  for (double x : {-4.0, 4.0}) {
    TriangleMesh q = quad_at(1.0, 2.0);
    for (dvec3& v : q.positions) v.x += x;
    b.add(std::move(q), kAlpha);
  }
  b.spot(dvec3(0.0, 6.0, 0.0), dvec3(0.0, -1.0, 0.0), 60.0);
  DsmSettings settings = unbiased_settings(kEps, 64);
  settings.clusters.max_clusters = 2;
  settings.clusters.d0 = 0.1;
  const HardMaps m = generate_maps(b.scene, GetParam(), settings);
  ASSERT_NE(m.maps->clusters(), nullptr);
  ASSERT_EQ(m.maps->layout().faces.size(), 2u) << "one cropped face per cluster";
  const std::vector<dvec3> points = {{-4.0, 0.0, 0.0}, {4.3, 0.0, -0.5}, {0.0, 0.0, 0.0},
                                     {-2.0, 0.0, 0.3}, {2.0, 0.5, -0.3}, {0.0, 0.0, 3.0}};
  const std::vector<double> expected = {0.5, 0.5, 1.0, 1.0, 1.0, 1.0};
  const std::vector<double> got = dsm_lookups(m, GetParam(), points, 0);
  Scene host_scene = b.scene;
  validate_scene(host_scene);
  const SceneData host(host_scene, Memory::host);
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_NEAR(oracle_at(host, 0, points[i]), expected[i], 1e-12) << "point " << i;
    EXPECT_NEAR(got[i], expected[i], kEps + 1e-6) << "point " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, HardLookups, ::testing::Values(Backend::cpu, Backend::cuda),
                         BackendName());

}  // namespace
}  // namespace dv::test
